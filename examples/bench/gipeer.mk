# gipeer.mk: voxlux's path-traced reference (raycast --set "illumination
# pathtrace") against a small Embree path tracer of the extracted mesh
# (peers/embree_pt.c), issue 21's "the path tracer against a peer"
# (included by the Makefile here; RESULTS-gipeer.md has the figures).
#
#   make -C examples/bench gipeer               ch2 at isovalues 40 and 127.5,
#                                                 512x512, spp 16, 1 and 2 threads
#   make -C examples/bench gipeer RUNS=1 GIP_SIZE=256 GIP_CASES=40   a quick look
#   make -C examples/bench gipeer GIP_REF_SPP=256  also both pictures at 256
#                                                 samples (noise against surface)
#   GIP_PACKETS=0                                leave out embree_pt --packets
#
# The scene: a sky, a directional light with shadows, one bounce, Lambertian
# albedo (the surface of examples/scenes/head-gi.scn, whose light is an
# environment map), with the benchmark camera of the ch2 dataset (ch2_ISOCAM); gipeer.py writes it as
# a voxlux scene and as embree_pt's flags, runs both tools round by round
# (time per path, the marginal cost of a sample), compares the pictures
# and runs giprobe (the GI rays' work per ray).  Results in results/gipeer/
# (gipeer.md, gipeer.json, the pictures as PFM and PNG); not part of
# `make test`.  Needs voxlux built (`make` at the top) and the peers'
# packages (bench-deps).

GIP_CASES ?= 40 127.5
GIP_SIZE ?= 512
GIP_SPP ?= 16
GIP_REF_SPP ?= 0
GIP_PACKETS ?= 1
GIP_THREADS ?= $(sort 1 $(NT))
GIP_OUT ?= results/gipeer
GIPROBE := $(OUT)/giprobe

.PHONY: gipeer gipeer-clean

$(GIPROBE): giprobe.c $(VX_LIB)
	@mkdir -p $(@D)
	$(CC) -std=c11 -O2 -g -Wall -Wextra -Wshadow -Wno-unused-parameter -fopenmp \
	  $(VX_INC) -o $@ $< $(VX_LIB) -lpng -lz -lm

gipeer: $(EMBREE_PT) $(GIPROBE) $(OUT)/ch2.nrrd $(OUT)/ch2-b.vx
	@for p in raycast tonemap; do [ -x $(VX_BIN)/$$p ] || \
	  { echo "gipeer: $(VX_BIN)/$$p missing: run make at the top first" >&2; exit 69; }; done
	$(PY) gipeer.py --out $(GIP_OUT) --work $(OUT)/gipeer --bin $(VX_BIN) \
	  --embree-pt $(EMBREE_PT) --probe $(GIPROBE) --nrrd $(OUT)/ch2.nrrd \
	  --stream $(OUT)/ch2-b.vx $(foreach c,$(GIP_CASES),--case $(c)) \
	  --size $(GIP_SIZE) --spp $(GIP_SPP) --ref-spp $(GIP_REF_SPP) \
	  --threads "$(GIP_THREADS)" --runs $(RUNS) --camera "$(ch2_ISOCAM)" \
	  $(if $(filter 1,$(GIP_PACKETS)),--packets)

gipeer-clean:
	rm -rf $(GIP_OUT) $(OUT)/gipeer $(EMBREE_PT) $(GIPROBE)
