# voxlux: one non-recursive GNU Makefile.
#
#   make              build/libvoxlux.a and every program into bin/
#   make test         unit tests (cmocka) and command-line tests
#   make SANITIZE=1 test   the same under ASan+UBSan, float-cast-overflow
#                          included (separate build dir)
#   make deps         install the Debian packages the build and tests need
#   make install PREFIX=/usr/local [DESTDIR=...]
#   make fuzz         libFuzzer targets (clang) over the committed corpus
#   make bench        benchmarks (see examples/bench)
#   make demo         the README's first command
#   make cloud        a coarse volume made a cloud by dvr's noise (examples/cloud)
#
# New modules, programs and tests are picked up by wildcard: a file in a
# layer folder of src/core/ (LAYERS, in order) joins the library (.c, and
# .cc for the C++ of a library that has no C API: OpenEXR's),
# src/tools/NAME.c becomes bin/NAME,
# tests/unit/test_NAME.c becomes a unit test, tests/cli/test_*.sh a CLI test.

CC ?= cc
PREFIX ?= /usr/local
SANITIZE ?=
OPT ?= -O2

ifeq ($(SANITIZE),1)
BUILD := build/san
BINDIR := build/san/bin
SANFLAGS := -fsanitize=address,undefined,float-cast-overflow -fno-omit-frame-pointer \
	-fno-sanitize-recover=undefined,float-cast-overflow
# C++: no vptr checks (their runtime is the C++ driver's, and we link with CC)
SANFLAGS_CXX := $(SANFLAGS) -fno-sanitize=vptr
OPT := -O1 -g
else
BUILD := build
BINDIR := bin
SANFLAGS :=
SANFLAGS_CXX :=
endif

# OpenMP: gcc always has it; clang needs libomp-dev.
OPENMP ?= -fopenmp
WARN := -Wall -Wextra -Wshadow -Wno-unused-parameter
# `override`: a CFLAGS given on the command line (CI adds -Werror) keeps the
# language level, warnings and OpenMP instead of replacing them.
# The core's layers, each using only those before it (make check-layers).
LAYERS := util data io kernels light render bake dvr
CORE_INC := $(addprefix -Isrc/core/,$(LAYERS))
override CPPFLAGS += $(CORE_INC) -Isrc/tools/common -D_GNU_SOURCE
CFLAGS ?= $(OPT) -g
override CFLAGS += -std=c11 $(WARN) $(OPENMP) $(SANFLAGS) -MMD -MP
PNG_CFLAGS := $(shell pkg-config --cflags libpng 2>/dev/null)
PNG_LIBS := $(shell pkg-config --libs libpng 2>/dev/null || echo -lpng)
# OpenEXR (libopenexr-dev): its headers as system headers (no warnings of
# theirs), its C++ libraries and the C++ runtime for every program.
EXR_CFLAGS := $(patsubst -I%,-isystem %,$(shell pkg-config --cflags OpenEXR 2>/dev/null))
EXR_LIBS := $(shell pkg-config --libs OpenEXR 2>/dev/null || echo -lOpenEXR-3_1 -lIex-3_1 -lImath-3_1)
LDLIBS := $(PNG_LIBS) $(EXR_LIBS) -lstdc++ -lz -lm
override LDFLAGS += $(OPENMP) $(SANFLAGS)
override CPPFLAGS += $(PNG_CFLAGS)
# C++ (src/core/*/*.cc): the C compiler's family, the same warnings, and
# -Werror when CFLAGS has it.
ifeq ($(origin CXX),default)
CXX := $(if $(findstring clang,$(CC)),clang++,c++)
endif
CXXFLAGS ?= $(OPT) -g
override CXXFLAGS += -std=c++14 $(WARN) $(filter -Werror,$(CFLAGS)) $(SANFLAGS_CXX) $(EXR_CFLAGS) -MMD -MP

CORE_SRC := $(sort $(wildcard $(LAYERS:%=src/core/%/*.c)))
CORE_CXX := $(sort $(wildcard $(LAYERS:%=src/core/%/*.cc)))
CORE_OBJ := $(CORE_SRC:%.c=$(BUILD)/%.o) $(CORE_CXX:%.cc=$(BUILD)/%.o)
LIB := $(BUILD)/libvoxlux.a
COMMON_SRC := $(sort $(wildcard src/tools/common/*.c))
COMMON_OBJ := $(COMMON_SRC:%.c=$(BUILD)/%.o)
TOOL_SRC := $(sort $(wildcard src/tools/*.c))
TOOLS := $(TOOL_SRC:src/tools/%.c=$(BINDIR)/%)
UNIT_SRC := $(sort $(wildcard tests/unit/test_*.c))
UNIT := $(UNIT_SRC:tests/unit/%.c=$(BUILD)/tests/%)
UNIT_HELP := $(sort $(wildcard tests/unit/helper_*.c))
UNIT_HELP_OBJ := $(UNIT_HELP:%.c=$(BUILD)/%.o)
HEADERS := $(sort $(wildcard $(LAYERS:%=src/core/%/vx_*.h)))
FUZZ_SRC := $(sort $(wildcard tests/fuzz/fuzz_*.c))
FUZZ := $(FUZZ_SRC:tests/fuzz/%.c=build/fuzz/%)
FUZZ_TIME ?= 30

.SECONDARY:
.DELETE_ON_ERROR:

.PHONY: all test unit cli check-layers print-core-inc deps install uninstall fuzz fuzz-build bench demo cloud \
	studies clean check-deps
all: $(LIB) $(TOOLS)

# Objects depend on this file too: a change of flags here (HOT_OBJ's, say)
# rebuilds them instead of leaving old code in place.
$(BUILD)/%.o: %.c Makefile
	@mkdir -p $(@D)
	$(CC) $(CPPFLAGS) $(CFLAGS) -c -o $@ $<

$(BUILD)/%.o: %.cc Makefile
	@mkdir -p $(@D)
	$(CXX) $(CPPFLAGS) $(CXXFLAGS) -c -o $@ $<

# The isosurface kernels (the hierarchy, its walks and cell masks, cells,
# the render loop, the camera's rays, dvr's slice passes) at -O3 -fno-math-errno
# -fno-trapping-math, after any CFLAGS: the same bits as at -O2 (no
# fast-math, -std=c11 keeps -ffp-contract=off, and these files read neither
# errno nor the FP flags and enable no traps), with no errno path for sqrt
# and floating-point selects without branches (README, "Rules").  Not under
# the sanitizers.
HOT_OBJ := $(addprefix $(BUILD)/src/core/,kernels/macro.o kernels/macrowalk.o \
	kernels/macrobox.o kernels/cellmask.o kernels/iso.o kernels/cell.o \
	render/raycast.o render/bins.o render/surface.o data/camera.o \
	data/irrvol.o render/gi.o bake/bake.o light/sh.o light/warp.o light/rng.o \
	dvr/dvr.o)
ifneq ($(SANITIZE),1)
$(HOT_OBJ): override CFLAGS += -O3 -fno-math-errno -fno-trapping-math
endif

$(LIB): $(CORE_OBJ)
	@mkdir -p $(@D)
	rm -f $@
	ar rcs $@ $^

$(BINDIR)/%: $(BUILD)/src/tools/%.o $(COMMON_OBJ) $(LIB)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(COMMON_OBJ) $(LIB) $(LDLIBS)

$(BUILD)/tests/%: $(BUILD)/tests/unit/%.o $(UNIT_HELP_OBJ) $(LIB)
	@mkdir -p $(@D)
	$(CC) $(LDFLAGS) -o $@ $< $(UNIT_HELP_OBJ) $(LIB) -lcmocka $(LDLIBS)

test: all $(UNIT) check-layers
	@VX_BIN=$(BINDIR) VX_UNIT_DIR=$(BUILD)/tests sh tests/run.sh

unit: $(UNIT)
	@VX_BIN=$(BINDIR) VX_UNIT_DIR=$(BUILD)/tests VX_ONLY=unit sh tests/run.sh

cli: all
	@VX_BIN=$(BINDIR) VX_UNIT_DIR=$(BUILD)/tests VX_ONLY=cli sh tests/run.sh

# check-layers: no file of the core includes a header of a later layer, no
# header sits outside a layer, and every symbol the library exports starts
# with vx_ (tests/check-layers.sh says which file breaks which rule).
check-layers: $(LIB)
	@sh tests/check-layers.sh $(LIB) $(LAYERS)

# The compiler flags that find the core's headers, for programs built
# outside this Makefile (examples/bench): $(make -s print-core-inc).
print-core-inc:
	@echo $(CORE_INC)

# ---- dependencies (Debian) ----
DEB_BUILD := build-essential pkg-config libpng-dev zlib1g-dev libcmocka-dev libopenexr-dev
DEB_TEST := mricron-data python3 strace gnuplot-nox blender-data teem-apps
DEB_FUZZ := clang libclang-rt-14-dev libomp-dev
deps:
	@missing=""; for p in $(DEB_BUILD) $(DEB_TEST) $(DEB_FUZZ) $(DEB_EXTRA); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "installing:$$missing"; \
	  SUDO=; [ "$$(id -u)" = 0 ] || SUDO=sudo; \
	  $$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq $$missing >/dev/null; \
	else echo "all Debian packages present"; fi

# ---- install ----
install: all
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/lib/pkgconfig \
	  $(DESTDIR)$(PREFIX)/include/voxlux $(DESTDIR)$(PREFIX)/share/man/man1 \
	  $(DESTDIR)$(PREFIX)/share/man/man5 $(DESTDIR)$(PREFIX)/share/man/man7
	install -m 755 $(TOOLS) $(DESTDIR)$(PREFIX)/bin
	install -m 644 $(LIB) $(DESTDIR)$(PREFIX)/lib
	install -m 644 $(HEADERS) $(DESTDIR)$(PREFIX)/include/voxlux
	for s in 1 5 7; do for f in man/man$$s/*.$$s; do [ -e "$$f" ] && \
	  install -m 644 $$f $(DESTDIR)$(PREFIX)/share/man/man$$s; done; done; true
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|'"$$(sed -n 's/.*VX_VERSION "\(.*\)".*/\1/p' src/core/util/vx_version.h)"'|' \
	  voxlux.pc.in > $(DESTDIR)$(PREFIX)/lib/pkgconfig/voxlux.pc

uninstall:
	for t in $(TOOLS); do rm -f $(DESTDIR)$(PREFIX)/bin/$$(basename $$t) \
	  $(DESTDIR)$(PREFIX)/share/man/man1/$$(basename $$t).1; done
	for s in 5 7; do for f in man/man$$s/*.$$s; do [ -e "$$f" ] && \
	  rm -f $(DESTDIR)$(PREFIX)/share/man/man$$s/$$(basename $$f); done; done; true
	rm -rf $(DESTDIR)$(PREFIX)/include/voxlux
	rm -f $(DESTDIR)$(PREFIX)/lib/libvoxlux.a $(DESTDIR)$(PREFIX)/lib/pkgconfig/voxlux.pc

# ---- fuzzing (clang + libFuzzer) ----
# The core is compiled once with sanitizer coverage into its own archive;
# each tests/fuzz/fuzz_NAME.c links against it.  OpenMP as in the normal
# build (clang needs libomp-dev); run.sh sets OMP_NUM_THREADS=1.  UBSan
# findings abort, so libFuzzer keeps them as crashes.
FUZZ_SAN := -fsanitize=address,undefined,float-cast-overflow \
	-fno-sanitize-recover=undefined,float-cast-overflow
FUZZ_CFLAGS := -g -O1 -fno-omit-frame-pointer $(FUZZ_SAN) $(OPENMP) $(CORE_INC) -D_GNU_SOURCE $(PNG_CFLAGS)
FUZZ_OBJ := $(CORE_SRC:src/core/%.c=build/fuzz/obj/%.o) $(CORE_CXX:src/core/%.cc=build/fuzz/obj/%.o)
FUZZ_LIB := build/fuzz/libvoxlux-fuzz.a
build/fuzz/obj/%.o: src/core/%.c
	@mkdir -p $(@D)
	clang $(FUZZ_CFLAGS) -fsanitize=fuzzer-no-link -MMD -MP -c -o $@ $<

build/fuzz/obj/%.o: src/core/%.cc
	@mkdir -p $(@D)
	clang++ -std=c++14 $(FUZZ_CFLAGS) -fno-sanitize=vptr,function $(EXR_CFLAGS) -fsanitize=fuzzer-no-link -MMD -MP -c -o $@ $<

$(FUZZ_LIB): $(FUZZ_OBJ)
	rm -f $@
	ar rcs $@ $^

build/fuzz/%: tests/fuzz/%.c tests/fuzz/fuzz.h tests/fuzz/fuzz_env.h $(FUZZ_LIB)
	clang $(FUZZ_CFLAGS) -fsanitize=fuzzer -o $@ $< $(FUZZ_LIB) $(LDLIBS)

fuzz-build: $(FUZZ)

fuzz: fuzz-build
	FUZZ_TIME=$(FUZZ_TIME) sh tests/fuzz/run.sh $(FUZZ)

# ---- examples ----
demo: all
	sh examples/demo.sh

bench: all
	$(MAKE) -C examples/bench

studies: all
	$(MAKE) -C examples/studies

cloud: all
	$(MAKE) -C examples/cloud

clean:
	rm -rf build bin/*

-include $(CORE_OBJ:.o=.d) $(COMMON_OBJ:.o=.d) $(TOOL_SRC:src/tools/%.c=$(BUILD)/src/tools/%.d) \
	$(UNIT_SRC:%.c=$(BUILD)/%.d) $(FUZZ_OBJ:.o=.d)
