# gi.mk: global illumination (Wyman et al. 2006): bake-irr and raycast's
# irradiance shading (included by the Makefile here; RESULTS-gi.md has the
# tables, the setup and what they mean).
#
#   make -C examples/bench gi              Tables 1 and 2, accuracy, memory: results/gi/
#   make -C examples/bench gi GI_PARTS=t2 RUNS=3      one part: t1, t2, acc, mem
#   make -C examples/bench gi GI_SAMPLES=16,100       fewer sample counts
#   make -C examples/bench gi-sh           bake-sh and SH shading (issue 22): Table 1's
#                                          SH rows, Table 2 with the SH frames, the
#                                          cost a path against bake-irr, memory: results/gi-sh/
#   make -C examples/bench gi-sh GI_SH_PARTS=shmem    one part: sht1, t2, shcost, shmem
#   make -C examples/bench gi-t2           Table 2 in one process (t2bench.c: every
#                                          mode each round, GI_T2_ROUNDS rounds, 1 thread):
#                                          results/gi-t2/t2bench.txt
#   make -C examples/bench gi-probe        where a bake's paths go (bakeprobe.c):
#                                          results/gi-t2/bakeprobe.txt
#
# Datasets: the MRI head (ch2, skin at 40: examples/scenes/head-gi-sky.scn) and,
# when $(DATA) has it, the Visible Human CT head (skin at 600.5:
# examples/scenes/vhf-gi.scn); GI_RANGE_D is each one's --iso-range band.
# Bakes of more than GI_MAX_PATHS paths (lazy images: GI_MAX_LAZY_PATHS)
# are extrapolated from the measured ones, and the tables say so
# (gibench.py).  Needs voxlux built (`make` at the top).

GI_OUT ?= results/gi
GI_PARTS ?= t1,t2,acc,mem
GI_SAMPLES ?= 16,100,625
GI_MAX_PATHS ?= 2e7
GI_MAX_LAZY_PATHS ?= 8e7
GI_CASES ?= ch2 $(if $(wildcard $(vhf_SRC)),vhf)
ch2_GISCENE := ../scenes/head-gi-sky.scn
ch2_GIRANGE := 30,50
vhf_GISCENE := ../scenes/vhf-gi.scn
vhf_GIRANGE := 500,700

GI_SH_OUT ?= results/gi-sh
GI_SH_PARTS ?= sht1,t2,shcost,shmem
GI_SH_MAX_LAZY_PATHS ?= 2e7
GI_SH_ORDER ?= 5
# the CT head's skin-to-bone band for the memory prediction (gibench.py)
GI_SH_VHF_BAND ?= 600.5,1224.5

GI_T2_OUT ?= results/gi-t2
GI_T2_ROUNDS ?= 41
GI_T2_THREADS ?= 1

.PHONY: gi gi-sh gi-t2 gi-probe

$(OUT)/gi/%.vx: $$($$*_SRC)
	@mkdir -p $(@D)
	$(VX_BIN)/vread $($*_VREAD) $< | $(VX_BIN)/brick | $(VX_BIN)/macrocell > $@.tmp && mv $@.tmp $@

gi: $(foreach c,$(GI_CASES),$(OUT)/gi/$(c).vx)
	@for p in vread brick macrocell bake-irr raycast vinfo; do [ -x $(VX_BIN)/$$p ] || \
	  { echo "gi: $(VX_BIN)/$$p missing: run make at the top first" >&2; exit 69; }; done
	$(PY) gibench.py --bin $(VX_BIN) --out $(GI_OUT) --runs $(RUNS) --parts $(GI_PARTS) \
	  --samples $(GI_SAMPLES) --max-paths $(GI_MAX_PATHS) --max-lazy-paths $(GI_MAX_LAZY_PATHS) \
	  $(foreach c,$(GI_CASES),--dataset $(c) $(OUT)/gi/$(c).vx $($(c)_GISCENE) $($(c)_GIRANGE))

gi-sh: $(foreach c,$(GI_CASES),$(OUT)/gi/$(c).vx)
	@for p in vread brick macrocell bake-irr bake-sh raycast vinfo; do [ -x $(VX_BIN)/$$p ] || \
	  { echo "gi-sh: $(VX_BIN)/$$p missing: run make at the top first" >&2; exit 69; }; done
	$(PY) gibench.py --bin $(VX_BIN) --out $(GI_SH_OUT) --runs $(RUNS) --parts $(GI_SH_PARTS) \
	  --samples $(GI_SAMPLES) --max-paths $(GI_MAX_PATHS) --max-lazy-paths $(GI_SH_MAX_LAZY_PATHS) \
	  --sh-order $(GI_SH_ORDER) --sh-vhf-band $(GI_SH_VHF_BAND) \
	  $(foreach c,$(GI_CASES),--dataset $(c) $(OUT)/gi/$(c).vx $($(c)_GISCENE) $($(c)_GIRANGE))

# Table 2 in one process: the ch2 band's bake at 4 samples a texel (the
# frame time does not depend on the count) in each store
$(OUT)/t2bench $(OUT)/bakeprobe: $(OUT)/%: %.c $(VX_LIB)
	@mkdir -p $(@D)
	$(CC) -std=c11 -O2 -g -Wall -Wextra -Wshadow -Wno-unused-parameter -fopenmp \
	  $(VX_INC) -o $@ $< $(VX_LIB) -lpng -lz -lm

$(OUT)/gi-t2/ch2-accum.vx: $(OUT)/gi/ch2.vx
	@mkdir -p $(@D)
	$(VX_BIN)/bake-irr --scene $(ch2_GISCENE) --samples 4 -o $@.tmp $< && mv $@.tmp $@

$(OUT)/gi-t2/ch2-f32.vx $(OUT)/gi-t2/ch2-f16.vx: $(OUT)/gi-t2/ch2-%.vx: $(OUT)/gi-t2/ch2-accum.vx
	$(VX_BIN)/bake-irr --scene $(ch2_GISCENE) --samples 0 \
	  $(if $(filter f32,$*),--final,--half) -o $@.tmp $< && mv $@.tmp $@

gi-t2: $(OUT)/t2bench $(foreach s,accum f32 f16,$(OUT)/gi-t2/ch2-$(s).vx)
	@mkdir -p $(GI_T2_OUT)
	$(OUT)/t2bench --scene $(ch2_GISCENE) -n $(GI_T2_ROUNDS) -j $(GI_T2_THREADS) \
	  $(foreach s,accum f32 f16,--irr $(s)=$(OUT)/gi-t2/ch2-$(s).vx) \
	  $(OUT)/gi/ch2.vx > $(GI_T2_OUT)/t2bench.txt && cat $(GI_T2_OUT)/t2bench.txt

gi-probe: $(OUT)/bakeprobe $(OUT)/gi/ch2.vx
	@mkdir -p $(GI_T2_OUT)
	$(OUT)/bakeprobe --scene $(ch2_GISCENE) --samples 4 --every 8 \
	  $(OUT)/gi/ch2.vx > $(GI_T2_OUT)/bakeprobe.txt && cat $(GI_T2_OUT)/bakeprobe.txt
