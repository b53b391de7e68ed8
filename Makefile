# umppmFoam -- build, tests, sanitizers, fuzzing.
#   make            release build: build/release/umppmFoam (+ ./bin/umppmFoam link)
#   make run        install Debian packages if missing, build, run tutorials/cavity
#   make check      the whole test suite (-Werror build, unit + OpenFOAM
#                   integration tests, every figure asserted; then all of them
#                   again under ASan/UBSan, the long runs short: make asan)
#   make asan       unit and integration tests under AddressSanitizer + UBSan (clang),
#                   the long accuracy runs cut to a few steps
#   make debug      -O0 -g -DUMP_DEBUG build in build/debug
#   make fuzz       libFuzzer harnesses: FoamFile, polyMesh + 2-D mesh, field reader (clang)
#   make deps       install the Debian packages (apt-get, needs root or sudo)
# Every build uses OpenMP (gcc's -fopenmp/libgomp; clang's libomp for the
# sanitizer build): OMP_NUM_THREADS sets the solver's threads.

CC      ?= cc
BUILD   ?= build/release
OPT     ?= -O2 -g
WERROR  ?=
SAN     ?=
OMP     ?= -fopenmp
# Floating point: no errno from sqrt (so the kernels' omp simd loops
# vectorise with it); contraction into FMA where the ISA has it (baseline
# x86-64 has none, so only the AVX2/FMA kernel clones change).
FPFLAGS ?= -fno-math-errno -ffp-contract=fast
CPPFLAGS = -Iinclude -I/usr/include/suitesparse -D_XOPEN_SOURCE=700
CFLAGS_ALL = -std=c11 -Wall -Wextra -Wpedantic -Wshadow -Wvla $(WERROR) $(OPT) $(OMP) $(FPFLAGS) $(SAN)
LDLIBS  = -lumfpack -lklu -lcholmod -lamd -lcolamd -lsuitesparseconfig -lqhull_r -lz -lm
TEST_LDLIBS = -lcmocka
NPROC   := $(shell nproc 2>/dev/null || echo 1)

# libopenblas0-serial: Debian then points libblas.so.3 at OpenBLAS (single
# threaded) instead of the reference BLAS, so UMFPACK's and CHOLMOD's dense
# kernels are optimised: the PPE factorization at start-up takes half the time.
DEB_PACKAGES = build-essential clang libclang-rt-14-dev libomp-14-dev libsuitesparse-dev libopenblas0-serial \
               zlib1g-dev libcmocka-dev libqhull-dev openfoam openfoam-examples gmsh gnuplot-nox

LIB_SRC  = $(filter-out src/main.c src/main_meshless.c,$(wildcard src/*.c))
LIB_OBJ  = $(LIB_SRC:src/%.c=$(BUILD)/obj/%.o)
LIB      = $(BUILD)/libumppm.a
APP      = $(BUILD)/umppmFoam
MLAPP    = $(BUILD)/meshlessFoam
UNIT_SRC = $(wildcard tests/unit/test_*.c)
UNIT_BIN = $(UNIT_SRC:tests/unit/%.c=$(BUILD)/tests/%)

.PHONY: all run check unit integration test-programs asan debug fuzz deps clean
.SECONDARY:

TOOLS    = $(patsubst tools/%.c,$(BUILD)/tools/%,$(wildcard tools/*.c))

all: $(APP) $(MLAPP) $(TOOLS)
	@mkdir -p bin && ln -sf ../$(APP) bin/umppmFoam && ln -sf ../$(MLAPP) bin/meshlessFoam
	@for t in $(TOOLS); do ln -sf ../$$t bin/$$(basename $$t); done

$(BUILD)/tools/%: tools/%.c $(LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) -DUMPPM_TOOLS_REF='"$(abspath tools/reference)"' $(CFLAGS_ALL) -o $@ $< $(LIB) $(LDLIBS)

$(BUILD)/obj/%.o: src/%.c $(wildcard include/umppm/*.h) $(wildcard src/*.h)
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(CFLAGS_ALL) -c $< -o $@

$(LIB): $(LIB_OBJ)
	@mkdir -p $(dir $@)
	ar rcs $@ $^

$(APP): $(BUILD)/obj/main.o $(LIB)
	$(CC) $(CFLAGS_ALL) -o $@ $^ $(LDLIBS)

$(MLAPP): $(BUILD)/obj/main_meshless.o $(LIB)
	$(CC) $(CFLAGS_ALL) -o $@ $^ $(LDLIBS)

$(BUILD)/tests/%: tests/unit/%.c $(wildcard tests/unit/*.h) $(wildcard src/*.h) $(LIB)
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) -Itests/unit $(CFLAGS_ALL) -o $@ $< $(LIB) $(TEST_LDLIBS) $(LDLIBS)

# Unit tests of one build flavour: each binary runs from the repository root.
unit: $(UNIT_BIN) $(APP)
	@set -e; for t in $(UNIT_BIN); do echo "== $$t"; $$t; done

# Tests against OpenFOAM's own tools (blockMesh, gmshToFoam, postProcess...).
INTEGRATION_PROGS = $(APP) $(MLAPP) $(TOOLS) $(BUILD)/geomcheck $(BUILD)/write_cavity_fields $(BUILD)/write_cloud \
                    $(BUILD)/killshim.so $(BUILD)/editshim.so

# Everything the tests run, built with -j before they start.
test-programs: $(UNIT_BIN) $(INTEGRATION_PROGS)

integration: $(INTEGRATION_PROGS)
	@UMPPMFOAM=$(abspath $(APP)) MESHLESSFOAM=$(abspath $(MLAPP)) GEOMCHECK=$(abspath $(BUILD)/geomcheck) \
	    KILLSHIM=$(abspath $(BUILD)/killshim.so) \
	    EDITSHIM=$(abspath $(BUILD)/editshim.so) \
	    WRITE_CAVITY_FIELDS=$(abspath $(BUILD)/write_cavity_fields) \
	    WRITE_CLOUD=$(abspath $(BUILD)/write_cloud) TOOLDIR=$(abspath $(BUILD)/tools) tests/integration/run_all.sh

# The LD_PRELOAD shim of test_nothing_lost.sh (SIGKILL at the k-th write
# call): a plain shared object, never sanitized (it is preloaded).
$(BUILD)/killshim.so: tests/integration/killshim.c tests/integration/shim.h
	@mkdir -p $(dir $@)
	$(CC) -shared -fPIC -std=c11 -Wall -Wextra -Wpedantic $(WERROR) -O2 -o $@ $< -ldl

# The LD_PRELOAD shim of test_runtime_modifiable.sh (renames a prepared
# controlDict over the case's when a chosen time directory is made).
$(BUILD)/editshim.so: tests/integration/editshim.c tests/integration/shim.h
	@mkdir -p $(dir $@)
	$(CC) -shared -fPIC -std=c11 -Wall -Wextra -Wpedantic $(WERROR) -O2 -o $@ $< -ldl

$(BUILD)/%: tests/integration/%.c $(LIB)
	$(CC) $(CPPFLAGS) $(CFLAGS_ALL) -o $@ $< $(LIB) $(LDLIBS)

# README command 1: install what is missing, build, run the default tutorial.
run: deps
	$(MAKE) all
	tutorials/cavity/Allclean && tutorials/cavity/Allrun

# README command 2 (and .ci/run): the whole test suite, from nothing.
# The programs are built NPROC at a time; the integration tests run NPROC
# at a time, one thread each (tests/integration/run_all.sh).
check: deps
	$(MAKE) -j$(NPROC) BUILD=build/check WERROR=-Werror test-programs
	$(MAKE) BUILD=build/check WERROR=-Werror unit
	UMPPM_TEST_SHORT= UMPPM_KILL_STRIDE= $(MAKE) BUILD=build/check WERROR=-Werror integration
	$(MAKE) asan

# -Wno-pass-failed: at -O1 under the sanitizers clang does not vectorise the
# kernels' `omp simd` loops (a hint, not a requirement).
ASAN_VARS = BUILD=build/asan CC=clang WERROR=-Werror OPT="-O1 -g -fno-omit-frame-pointer" \
            SAN="-fsanitize=address,undefined -fno-sanitize-recover=all -Wno-pass-failed"
# UMPPM_TEST_SHORT=1: the integration tests' long accuracy runs go a few
# steps (their figures are asserted by the plain pass of `make check`), and
# the OpenFOAM reference runs are left out (tests/integration/lib.sh).
asan:
	$(MAKE) -j$(NPROC) $(ASAN_VARS) test-programs
	UMPPM_KILL_STRIDE=8 UMPPM_TEST_SHORT=1 $(MAKE) $(ASAN_VARS) unit integration

debug:
	$(MAKE) BUILD=build/debug OPT="-O0 -g -DUMP_DEBUG" all

# Harnesses: the FoamFile reader, the polyMesh reader + 2-D mesh, the field
# reader (tests/fuzz/; corpora tests/fuzz/corpus*, README "Tests").
FUZZERS = $(BUILD)/fuzz_foam $(BUILD)/fuzz_polymesh $(BUILD)/fuzz_field
fuzz: $(FUZZERS)
$(BUILD)/fuzz_%: tests/fuzz/fuzz_%.c $(LIB_SRC) $(wildcard include/umppm/*.h) $(wildcard src/*.h)
	@mkdir -p $(dir $@)
	clang $(CPPFLAGS) -std=c11 -g -O1 -fsanitize=fuzzer,address,undefined -o $@ $< $(LIB_SRC) $(LDLIBS)

deps:
	@missing=""; for p in $(DEB_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  SUDO=""; [ "$$(id -u)" = 0 ] || SUDO=sudo; \
	  echo "Installing:$$missing"; \
	  $$SUDO apt-get update && DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y $$missing; \
	else echo "All Debian packages present."; fi

clean:
	rm -rf build bin
