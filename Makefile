# hairbsdf. `make` builds the libraries and the tool into build/<arch>-<compiler>/, `make test`
# runs the quick tier of the tests on every ISA this CPU has, `make check` the long tier,
# `make bench` times the kernels against bench/budgets.txt, `make demo` shows the main job.
# `make test CROSS=aarch64` cross-compiles with gcc-aarch64-linux-gnu and runs the suite under
# qemu-aarch64; `make test CROSS=mingw` with MinGW-w64 for Windows, run under wine. `make CC=clang`
# builds with clang.

MAKEFLAGS += --no-builtin-rules
.SUFFIXES:

CROSS ?=
STRIP ?= strip
EXE :=
PIC := -fPIC
PLATFORM_CFLAGS :=
ifeq ($(CROSS),aarch64)
  CC := aarch64-linux-gnu-gcc
  AR := aarch64-linux-gnu-ar
  STRIP := aarch64-linux-gnu-strip
  ARCH := aarch64
  RUN := qemu-aarch64
  LDSTATIC := -static
else ifeq ($(CROSS),mingw)
  CC := x86_64-w64-mingw32-gcc
  AR := x86_64-w64-mingw32-ar
  STRIP := x86_64-w64-mingw32-strip
  ARCH := x86_64
  RUN := WINEDEBUG=-all wine
  LDSTATIC := -static
  EXE := .exe
  PIC := # every Windows image is position independent
  # C99 printf formats (%zu); the static library; and unaligned moves for vector spills, since GCC
  # assumes a 32- or 64-byte aligned stack for AVX locals that Windows aligns to 16 (GCC bug 54412)
  PLATFORM_CFLAGS := -D__USE_MINGW_ANSI_STDIO=1 -DHB_STATIC -Wa,-muse-unaligned-vector-move
else ifneq ($(CROSS),)
  $(error CROSS=$(CROSS) is not supported; use CROSS=aarch64 or CROSS=mingw)
else
  ARCH := $(shell uname -m)
  RUN :=
  LDSTATIC :=
endif

SANITIZE ?=
TSAN ?=
PREFIX ?= /usr/local
FUZZ ?=
B := build/$(ARCH)-$(notdir $(firstword $(CC)))$(if $(SANITIZE),-san)$(if $(TSAN),-tsan)$(if $(FUZZ),-fuzz)

ifeq ($(ARCH),x86_64)
  ISAS := scalar sse41 avx2 avx512
else ifeq ($(ARCH),aarch64)
  ISAS := scalar neon
else
  ISAS := scalar
endif

ISA_FLAGS_scalar := -fno-tree-vectorize
ISA_FLAGS_sse41 := -msse4.1
ISA_FLAGS_avx2 := -mavx2 -mfma
ISA_FLAGS_avx512 := -mavx512f -mavx2 -mfma
ISA_FLAGS_neon :=
ISA_MACRO_scalar := HB_TARGET_SCALAR
ISA_MACRO_sse41 := HB_TARGET_SSE41
ISA_MACRO_avx2 := HB_TARGET_AVX2
ISA_MACRO_avx512 := HB_TARGET_AVX512
ISA_MACRO_neon := HB_TARGET_NEON

WARN := -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes
# No -ffast-math and no implicit contraction: every fused multiply-add is explicit,
# so results are reproducible per ISA. No SLP vectorization either: GCC 12.2's folds
# (double)(float)x back to x when it pairs such statements (x - (double)(float)x became 0 in
# plan.c's float splitting), and the kernels vectorize by hand.
CFLAGS ?= -O2 -g
BASE_CFLAGS := -std=c11 -D_GNU_SOURCE $(PLATFORM_CFLAGS) $(WARN) $(PIC) -ffp-contract=off -fno-tree-slp-vectorize -fno-math-errno -Iinclude -Isrc
ifneq ($(SANITIZE),)
  BASE_CFLAGS += -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -DHB_SANITIZED
  LDFLAGS += -fsanitize=address,undefined
endif
ifneq ($(TSAN),)
  BASE_CFLAGS += -fsanitize=thread -fno-omit-frame-pointer -DHB_SANITIZED
  LDFLAGS += -fsanitize=thread
endif
ifneq ($(FUZZ),)
  BASE_CFLAGS += -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -DHB_SANITIZED
endif
ALL_CFLAGS = $(BASE_CFLAGS) $(CFLAGS)
LDLIBS := -lm

# OpenEXR (optional, Debian's libopenexr-dev) for `hairbsdf dump -o FILE.exr`: found by
# pkg-config on native builds only; OPENEXR=0 builds without it even when it is installed.
OPENEXR ?= $(if $(CROSS),0,$(shell pkg-config --exists OpenEXR 2>/dev/null && echo 1 || echo 0))
ifeq ($(OPENEXR),1)
  $(B)/tools/image_exr.o: ALL_CFLAGS += -DHB_HAVE_OPENEXR $(shell pkg-config --cflags OpenEXR)
  EXR_LIBS := $(shell pkg-config --libs OpenEXR)
endif

# The layers (docs/architecture.md): every .c under src/ is compiled once, except each model's
# kernels.c, compiled once per ISA into $(B)/<isa>/ (the same ISAs as src/kernel/isas.h lists).
KERNEL_SRCS := $(wildcard src/models/*/kernels.c) src/dual/kernels.c
LIB_SRCS := $(filter-out $(KERNEL_SRCS),$(wildcard src/*/*.c src/*/*/*.c))
KERNEL_OBJS := $(foreach isa,$(ISAS),$(KERNEL_SRCS:%.c=$(B)/$(isa)/%.o))
LIB_OBJS := $(LIB_SRCS:%.c=$(B)/%.o) $(KERNEL_OBJS)
TOOL_SRCS := $(wildcard tools/*.c)
# tests/kernel_hooks.c reads kernel internals: compiled once per ISA like the kernels.
TEST_SRCS := $(filter-out tests/kernel_hooks.c,$(wildcard tests/*.c))
TEST_HOOK_OBJS := $(foreach isa,$(ISAS),$(B)/$(isa)/tests/kernel_hooks.o)
FUZZ_TARGETS := fuzz_cli fuzz_eval fuzz_table
BENCH_SRCS := $(wildcard bench/*.c)

STATIC_LIB := $(B)/libhairbsdf.a
# The version, from the public header: pkg-config's version and the soname's ABI version, which is
# major.minor while the major is 0 (a 0.x minor release may change the ABI; the header says so).
HB_VERSION_FIELD = $(shell sed -n 's/^\#define HB_VERSION_$(1) \([0-9]*\)$$/\1/p' include/hairbsdf.h)
HB_VERSION_MAJOR := $(call HB_VERSION_FIELD,MAJOR)
HB_VERSION_MINOR := $(call HB_VERSION_FIELD,MINOR)
HB_VERSION := $(HB_VERSION_MAJOR).$(HB_VERSION_MINOR).$(call HB_VERSION_FIELD,PATCH)
HB_SO_VERSION := $(if $(filter 0,$(HB_VERSION_MAJOR)),0.$(HB_VERSION_MINOR),$(HB_VERSION_MAJOR))
SHARED_LIB := $(B)/libhairbsdf.so.$(HB_SO_VERSION)
SHARED_LINK := $(B)/libhairbsdf.so
TOOL := $(B)/hairbsdf$(EXE)
EXAMPLE := $(B)/example_minimal$(EXE)
ENGINE_EXAMPLE := $(B)/example_engine$(EXE)
PATH_TRACER_EXAMPLE := $(B)/example_path_tracer$(EXE)
TEST_BIN := $(B)/hairbsdf_tests$(EXE)
BENCH_BIN := $(B)/hairbsdf_bench$(EXE)
REPLAYS := $(FUZZ_TARGETS:fuzz_%=$(B)/replay_fuzz_%$(EXE))
# The README's quick starts, compiled from its text and run by make test.
README_STARTS := $(B)/readme_engine$(EXE) $(B)/readme_path_tracer$(EXE)
.SECONDARY: $(B)/readme_engine.c $(B)/readme_path_tracer.c
FUZZ_TOOL_OBJS := $(B)/tools/csv.o $(B)/tools/cli_options.o $(B)/tools/cli_threads.o

.PHONY: all test check figures layers tsan bench bench-instr bench-instr-check calibration demo images fuzz fuzz-run install abi clean
all: $(STATIC_LIB) $(if $(LDSTATIC),,$(SHARED_LINK)) $(TOOL) $(EXAMPLE) $(ENGINE_EXAMPLE) $(PATH_TRACER_EXAMPLE)

$(B)/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(ALL_CFLAGS) -MMD -MP -c $< -o $@

# Library units export only what the public header marks HB_API.
LIB_ONLY_CFLAGS := -fvisibility=hidden -DHB_BUILDING_LIBRARY
$(B)/src/%.o: ALL_CFLAGS += $(LIB_ONLY_CFLAGS)

# The tests gain nothing from auto-vectorisation, and aarch64 gcc 12's vectoriser crashes
# (an internal compiler error) on some of their max-reductions.
$(B)/tests/%.o: ALL_CFLAGS += -fno-tree-vectorize -Itools -Ibench

# Kernel units carry line tables and function names (-g1: backtraces, perf and callgrind annotate
# by line): the locations of every variable of their inlined vector code took two thirds of their
# compile time and memory. KERNEL_CFLAGS=-g gives them full debug information.
KERNEL_CFLAGS ?= -g1
define KERNEL_RULE
$(B)/$(1)/%.o: %.c
	@mkdir -p $$(dir $$@)
	$$(CC) $$(ALL_CFLAGS) $$(LIB_ONLY_CFLAGS) $$(KERNEL_CFLAGS) $$(ISA_FLAGS_$(1)) -D$$(ISA_MACRO_$(1)) -MMD -MP -c $$< -o $$@
endef
$(foreach isa,$(ISAS),$(eval $(call KERNEL_RULE,$(isa))))

$(STATIC_LIB): $(LIB_OBJS)
	rm -f $@
	$(AR) rcs $@ $^

$(SHARED_LIB): $(LIB_OBJS)
	$(CC) -shared -Wl,-soname,libhairbsdf.so.$(HB_SO_VERSION) $(LDFLAGS) -o $@ $^ $(LDLIBS)

$(SHARED_LINK): $(SHARED_LIB)
	ln -sf $(notdir $<) $@

$(TOOL): $(TOOL_SRCS:%.c=$(B)/%.o) $(STATIC_LIB)
	$(CC) $(LDFLAGS) $(LDSTATIC) -o $@ $^ $(LDLIBS) $(EXR_LIBS) -lpthread

$(EXAMPLE): $(B)/examples/minimal.o $(STATIC_LIB)
	$(CC) $(LDFLAGS) $(LDSTATIC) -o $@ $^ $(LDLIBS)

# A quick start of README.md: the fenced block that opens with "/* README quick start: NAME */"
# (underscores in the file's name are spaces in NAME).
$(B)/readme_%.c: README.md
	@mkdir -p $(dir $@)
	awk -v name="$(subst _, ,$*)" '$$0 == "/* README quick start: " name " */" { on = 1 } on && /^```/ { exit } on' README.md > $@
	@test -s $@ || { echo "README.md has no quick start '$(subst _, ,$*)'"; rm -f $@; exit 1; }

# Every C block of docs/ compiled against the header, each as a function (tests/docs_blocks.awk).
DOCS_BLOCKS := $(B)/docs_blocks.o
$(B)/docs_blocks.c: $(wildcard docs/*.md) tests/docs_blocks.awk
	@mkdir -p $(dir $@)
	awk -f tests/docs_blocks.awk $(wildcard docs/*.md) > $@

$(DOCS_BLOCKS): $(B)/docs_blocks.c include/hairbsdf.h
	$(CC) $(ALL_CFLAGS) -Wno-unused-variable -Wno-unused-but-set-variable -c -o $@ $<

$(B)/readme_%$(EXE): $(B)/readme_%.c $(STATIC_LIB)
	$(CC) $(ALL_CFLAGS) $(LDFLAGS) $(LDSTATIC) -o $@ $< $(STATIC_LIB) $(LDLIBS)

$(PATH_TRACER_EXAMPLE): $(B)/examples/path_tracer.o $(STATIC_LIB)
	$(CC) $(LDFLAGS) $(LDSTATIC) -o $@ $^ $(LDLIBS)

$(ENGINE_EXAMPLE): $(B)/examples/engine.o $(STATIC_LIB)
	$(CC) $(LDFLAGS) $(LDSTATIC) -o $@ $^ $(LDLIBS)

$(TEST_BIN): $(TEST_SRCS:%.c=$(B)/%.o) $(TEST_HOOK_OBJS) $(B)/tools/image.o $(B)/tools/image_exr.o $(B)/bench/readme.o $(STATIC_LIB)
	$(CC) $(LDFLAGS) $(LDSTATIC) -o $@ $^ $(LDLIBS) $(EXR_LIBS) -lpthread

$(B)/bench/%.o: ALL_CFLAGS += -Itools

$(BENCH_BIN): $(BENCH_SRCS:%.c=$(B)/%.o) $(B)/tools/plot.o $(STATIC_LIB)
	$(CC) $(LDFLAGS) $(LDSTATIC) -o $@ $^ $(LDLIBS) -lpthread

# The runner loops over every ISA this CPU has (or those of $HB_TEST_ISAS or $HB_ISA) and drives the
# CLI through HB_TOOL. `make test` is the quick tier, `make check` the long one (every case of
# every test); TEST_FLAGS=--verbose prints each test's measurements.
# Under wine the runner starts the Windows tool itself (HB_TOOL is its path); under qemu HB_TOOL
# starts with the emulator, which is emulation (HB_TEST_EMULATED), while wine is not.
TEST_FLAGS ?=
TEST_TOOL := $(if $(filter mingw,$(CROSS)),$(TOOL),$(strip $(RUN) $(TOOL)))
RUN_TESTS = HB_TOOL="$(TEST_TOOL)" HB_TEST_EMULATED=$(if $(filter aarch64,$(CROSS)),1,0) $(RUN) $(TEST_BIN) $(TEST_FLAGS)
REPLAY_CORPUS = for t in $(FUZZ_TARGETS); do $(RUN) $(B)/replay_$$t$(EXE) tests/fuzz/corpus/$$t || exit 1; done
test: $(TEST_BIN) $(TOOL) $(REPLAYS) $(README_STARTS) $(PATH_TRACER_EXAMPLE) $(DOCS_BLOCKS)
	@$(REPLAY_CORPUS)
	@for x in $(README_STARTS) $(PATH_TRACER_EXAMPLE); do printf '%s: ' "$$(basename $$x)"; $(RUN) $$x || exit 1; done
	@$(RUN_TESTS)

# The include rules of docs/architecture.md: layer order, no model reading another, references
# free of the fast path, no branch on a model id outside src/models/.
layers:
	sh tests/layers.sh

check: $(TEST_BIN) $(TOOL) $(REPLAYS)
	@$(REPLAY_CORPUS)
	@$(RUN_TESTS) --long

# The long tier, writing what each test measured into the blocks of README.md and docs/ that name
# it (tests/figures.h).
figures: $(TEST_BIN) $(TOOL)
	@$(RUN_TESTS) --long --figures

# ThreadSanitizer (clang) over the test that shares plans between threads, kernels instrumented.
tsan:
	$(MAKE) CC=clang TSAN=1 test TEST_FLAGS="--filter threads"

# The fuzz harnesses without libFuzzer, replaying the kept corpus (make test runs them).
$(B)/replay_fuzz_%$(EXE): tests/fuzz/fuzz_%.c tests/fuzz/replay.c $(FUZZ_TOOL_OBJS) $(STATIC_LIB)
	$(CC) $(ALL_CFLAGS) -Itools $(LDFLAGS) $(LDSTATIC) -o $@ $^ $(LDLIBS) -lpthread

bench: $(BENCH_BIN)
	@mkdir -p bench/results
	$(RUN) $(BENCH_BIN) --results bench/results --budgets bench/budgets.txt --report docs/benchmarks.md --summary README.md

# The calibration tolerance and budget plans use by default: the last full `make bench` run's
# bench/results/calibration.csv, built into the library.
calibration:
	awk -F, 'NR > 1 && $$5 != "nan" { printf "    { \"%s\", \"%s\", \"%s\", %s, %s, %s },\n", $$1, $$2, $$3, $$4, $$5, ($$6 == "" ? 0 : $$6) }' \
	  bench/results/calibration.csv > src/plan/calibration_builtin.body
	{ echo '/* Generated by `make calibration` from bench/results/calibration.csv (model, configuration, ISA,'; \
	  echo ' * ns per sample, max error, the clock in GHz the ns were measured at). Do not edit. */'; cat src/plan/calibration_builtin.body; } > src/plan/calibration_builtin.h
	rm -f src/plan/calibration_builtin.body

# Instructions per sample under callgrind (repeatable, unlike time on a shared machine).
bench-instr: $(BENCH_BIN)
	bench/instr.sh $(BENCH_BIN)

# The instruction budgets of bench/instr_budgets.txt (callgrind, AVX2): a cost regression fails on
# any host, where the latency budgets of make bench depend on the host's state.
bench-instr-check: $(BENCH_BIN)
	bench/instr.sh $(BENCH_BIN) bench/instr_budgets.txt

# The main job on the default material: which ISA runs, the README example, f for a few
# directions (d'Eon 2011, full model, and its double reference beside it), the white furnace
# by lobe, the lobe images, and a few rows of the accuracy-and-cost table on the best ISA
# (budgets are enforced by make bench only).
DEMO_ROWS := theta_i,phi_i,theta_o,phi_o\n0.3,0,-0.37,0.5\n0.3,0,-0.2,3.0\n-1,0,1,2\n1.5,0,-1.5,3\n
demo: all $(BENCH_BIN)
	$(RUN) $(TOOL) isa
	$(RUN) $(EXAMPLE)
	$(RUN) $(ENGINE_EXAMPLE)
	printf '$(DEMO_ROWS)' | $(RUN) $(TOOL) eval --model deon --eumelanin 0.3
	printf '$(DEMO_ROWS)' | $(RUN) $(TOOL) eval --model deon --eumelanin 0.3 --quality reference
	$(RUN) $(TOOL) furnace --model deon --by-lobe --theta-o 0,0.8,1.45
	$(RUN) $(TOOL) dump --model deon --eumelanin 0.3 --theta-i 0.3 --exposure 2 -o $(B)/lobes_deon.png
	$(RUN) $(TOOL) dump --model deon --eumelanin 0.3 --theta-i 0.3 -o $(B)/lobes_deon.pfm
	printf '$(DEMO_ROWS)' | $(RUN) $(TOOL) eval --model marschner --eumelanin 0.3
	printf '$(DEMO_ROWS)' | $(RUN) $(TOOL) eval --model marschner --eumelanin 0.3 --quality reference
	$(RUN) $(TOOL) dump --model marschner --eumelanin 0.3 --theta-i 0.3 --exposure 2 -o $(B)/lobes_marschner.png
	printf '$(DEMO_ROWS)' | $(RUN) $(TOOL) eval --model huang --lobes R --eumelanin 0.3
	printf '$(DEMO_ROWS)' | $(RUN) $(TOOL) eval --model huang --lobes R --eumelanin 0.3 --quality reference
	$(RUN) $(TOOL) dump --model huang --eumelanin 0.3 --theta-i 0.3 --exposure 2 -o $(B)/lobes_huang.png
	$(RUN) $(TOOL) plan --model deon --eumelanin 1.8 --tolerance 1e-2
	@echo "lobe images: $(B)/lobes_deon.png, $(B)/lobes_marschner.png, $(B)/lobes_huang.png (tone-mapped) and $(B)/lobes_deon.pfm (float RGB)"
	$(RUN) $(BENCH_BIN) --demo

# libFuzzer (clang): CLI parsing and plan creation + evaluation, FUZZ_SECONDS per target; the
# corpus of interesting inputs is kept in tests/fuzz/corpus/ and replayed by later runs.
FUZZ_SECONDS ?= 60
fuzz:
	$(MAKE) CC=clang FUZZ=1 fuzz-run

fuzz-run: $(FUZZ_TARGETS:%=$(B)/%)
	for t in $(FUZZ_TARGETS); do mkdir -p tests/fuzz/corpus/$$t; \
	  $(B)/$$t -max_total_time=$(FUZZ_SECONDS) -print_final_stats=1 tests/fuzz/corpus/$$t || exit 1; done

$(B)/fuzz_%: tests/fuzz/fuzz_%.c $(FUZZ_TOOL_OBJS) $(STATIC_LIB)
	$(CC) $(ALL_CFLAGS) -Itools -fsanitize=fuzzer -o $@ $^ $(LDLIBS) -lpthread

# The README's pictures, by the commands the README shows.
images: $(TOOL)
	$(TOOL) dump --model deon --eumelanin 0.3 --theta-i 0.3 --exposure 2 --width 384 --height 192 \
	  -o docs/images/deon_brown_theta0.3.png
	$(TOOL) dump --model deon --theta-i -1.0 --beta-m 0.2 --beta-n 0.6 --exposure 2 --width 384 --height 192 \
	  -o docs/images/deon_white_theta-1.0.png
	$(TOOL) dump --model marschner --eumelanin 0.3 --theta-i 0.3 --exposure 2 --width 384 --height 192 \
	  -o docs/images/marschner_brown_theta0.3.png
	$(TOOL) dump --model huang --eumelanin 0.3 --theta-i 0.3 --exposure 2 --width 384 --height 192 \
	  -o docs/images/huang_brown_theta0.3.png
	$(TOOL) dump --model deon --eumelanin 0.3 --theta-i 0.3 --exposure 2 --width 256 --height 128 \
	  --compare model=huang -o docs/images/deon_vs_huang_theta0.3.png
	$(TOOL) furnace --model deon --by-lobe --theta-o -1.5,-1.25,-1,-0.75,-0.5,-0.25,0,0.25,0.5,0.75,1,1.25,1.5 \
	  --svg docs/images/deon_energy_by_lobe.svg > /dev/null
	$(TOOL) furnace --fig16 --paths 20000 --theta-o -1.4,-1.2,-1,-0.8,-0.6,-0.4,-0.2,0,0.2,0.4,0.6,0.8,1,1.2,1.4 \
	  --svg docs/images/huang_fig16_beyond_trt.svg > /dev/null
	$(TOOL) assembly --model chiang --eumelanin 0.3 --layers 16 --depth-bins 16 --paths 100000 \
	  --svg docs/images/assembly_blond_depth.svg > /dev/null
	$(TOOL) dual --model chiang --eumelanin 0.3 --svg docs/images/dual_blond_energies.svg > /dev/null
	$(TOOL) tress --eumelanin 0.3 --paths 8000000 --exposure 2 -o docs/images/tress_blond_front.png > /dev/null
	$(TOOL) tress --eumelanin 0.3 --paths 8000000 --view behind --exposure 0.5 -o docs/images/tress_blond_behind.png > /dev/null

# The pkg-config file is written at install time, so it always names this PREFIX.
install: all
	install -d $(DESTDIR)$(PREFIX)/include $(DESTDIR)$(PREFIX)/lib/pkgconfig $(DESTDIR)$(PREFIX)/bin
	install -m 644 include/hairbsdf.h $(DESTDIR)$(PREFIX)/include/
	install -m 644 $(STATIC_LIB) $(DESTDIR)$(PREFIX)/lib/
	install -m 755 $(SHARED_LIB) $(DESTDIR)$(PREFIX)/lib/
	ln -sf libhairbsdf.so.$(HB_SO_VERSION) $(DESTDIR)$(PREFIX)/lib/libhairbsdf.so
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(HB_VERSION)|' hairbsdf.pc.in > $(DESTDIR)$(PREFIX)/lib/pkgconfig/hairbsdf.pc
	install -m 755 $(TOOL) $(DESTDIR)$(PREFIX)/bin/
	install -d $(DESTDIR)$(PREFIX)/share/hairbsdf/shaders
	install -m 644 shaders/* $(DESTDIR)$(PREFIX)/share/hairbsdf/shaders/
	$(STRIP) --strip-debug $(DESTDIR)$(PREFIX)/lib/libhairbsdf.a $(DESTDIR)$(PREFIX)/lib/libhairbsdf.so.$(HB_SO_VERSION) \
	  $(DESTDIR)$(PREFIX)/bin/$(notdir $(TOOL))

# The shared library exports exactly the functions the public header declares with HB_API.
abi: $(SHARED_LIB)
	@nm -D --defined-only $(SHARED_LIB) | awk '$$2 == "T" { print $$3 }' | sort > $(B)/abi.exported
	@sed -n 's/^HB_API [^(]*[ *]\(hb_[a-z0-9_]*\)(.*/\1/p' include/hairbsdf.h | sort > $(B)/abi.declared
	@diff $(B)/abi.declared $(B)/abi.exported && echo "abi: $(SHARED_LIB) exports the $$(wc -l < $(B)/abi.declared) functions of include/hairbsdf.h, version $(HB_VERSION)"

clean:
	rm -rf build

-include $(shell find build -name '*.d' 2>/dev/null)
