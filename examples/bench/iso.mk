# iso.mk: voxlux's ray-cast isosurfaces against the extraction route, and
# Parker et al.'s Tables 1-3 (included by the Makefile here).
#
#   make -C examples/bench iso            every table below into results/ (RUNS=5 rounds)
#   make -C examples/bench iso ISO_ONLY=frames       one part: frames, latency, table3, sizes, pictures
#   make -C examples/bench iso ISO_CASES="ch2:127.5" RUNS=1   a quick look
#   make -C examples/bench corepair RUNS=9   alone against side by side (a shared core?)
#
# The picture: examples/scenes/iso-headlight.scn (one white Lambert surface,
# a headlight, no ambient: what embree_render draws), 512x512, with the
# peers' camera for each dataset (D_ISOCAM) in (a), (b) and the pictures,
# and auto-framed views in Table 3.  isobench.py interleaves the peers and
# voxlux round by round and writes results/*.md (tables) and *.json (the raw
# numbers); results/iso.md is all the tables.  The benchmark is not part of
# `make test`.
#
# Isovalues (stored units): ch2 127.5 (the issue's; the scalp and skull
# surface of the T1 image) and 40.5 (the skin); the VHF CT (HU = value -
# 1024) 600.5 (skin, HU -423.5, between air ~0 and soft tissue ~1040 in the
# histogram) and 1224.5 (bone, HU 200.5, above the soft-tissue peak's tail:
# the skull, face bones and teeth).  Half-integers so that no sample equals
# the isovalue.

RESULTS ?= results
ISO_SCENE := ../scenes/iso-headlight.scn
ISO_CASES ?= ch2:127.5 ch2:40.5 $(if $(wildcard $(vhf_SRC)),vhf:600.5 vhf:1224.5)
ISO_ONLY ?= frames,latency,table3,sizes,pictures
# Table 3 (five views, four layouts, the flat walks are slow): one case each
ISO_T3_CASES ?= ch2:127.5 $(if $(wildcard $(vhf_SRC)),vhf:1224.5)
ISO_DATASETS = $(sort $(foreach c,$(ISO_CASES),$(firstword $(subst :, ,$(c)))))
ISOBENCH := $(OUT)/isobench
# the view that shows the face: ch2 is stored RAS (face at +y), the VHF CT
# has its face at low y
ch2_FACE := front
vhf_FACE := back

.PHONY: iso iso-clean corepair

$(ISOBENCH): isobench.c $(VX_LIB)
	@mkdir -p $(@D)
	$(CC) -std=c11 -O2 -g -Wall -Wextra -Wshadow -Wno-unused-parameter -fopenmp \
	  $(VX_INC) -o $@ $< $(VX_LIB) -lpng -lz -lm

# voxlux's streams: bricked + macrocells (the default pipeline) and linear +
# macrocells (Table 3's unbricked columns)
$(OUT)/%-b.vx: $$($$*_SRC)
	@mkdir -p $(@D)
	$(VX_BIN)/vread $($*_VREAD) $< | $(VX_BIN)/brick | $(VX_BIN)/macrocell > $@.tmp && mv $@.tmp $@
$(OUT)/%-l.vx: $$($$*_SRC)
	@mkdir -p $(@D)
	$(VX_BIN)/vread $($*_VREAD) $< | $(VX_BIN)/macrocell > $@.tmp && mv $@.tmp $@

iso: $(ISOBENCH) $(EMBREE) $(foreach d,$(ISO_DATASETS),$(OUT)/$(d).nrrd $(OUT)/$(d)-b.vx $(OUT)/$(d)-l.vx)
	@mkdir -p $(RESULTS)
	$(PY) isobench.py --out $(RESULTS) --work $(OUT)/iso --runs $(RUNS) --bin $(VX_BIN) \
	  --isobench $(ISOBENCH) --embree $(EMBREE) --scene $(ISO_SCENE) --only $(ISO_ONLY) \
	  $(foreach d,$(ISO_DATASETS),--dataset $(d) $(OUT)/$(d).nrrd $(OUT)/$(d)-b.vx \
	    $(OUT)/$(d)-l.vx $($(d)_FACE) "$($(d)_ISOCAM)") \
	  $(foreach c,$(ISO_CASES),--case $(c)) $(foreach c,$(ISO_T3_CASES),--t3-case $(c))
	cd $(RESULTS) && cat $$(ls frames.md latency.md table3.md sizes.md pictures.md 2>/dev/null) > iso.md

# alone against side by side (coreprobe's two loops, voxlux, Embree): whether
# the two vCPUs share a core's execution units (RESULTS.md, "Two threads"); after
# `iso` has made the mesh
corepair: $(ISOBENCH) $(EMBREE) $(OUT)/ch2-b.vx
	sh corepair.sh $(RUNS)

iso-clean:
	rm -rf $(RESULTS) $(OUT)/iso $(OUT)/isobench $(OUT)/*-b.vx $(OUT)/*-l.vx
