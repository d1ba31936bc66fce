# whirl: steady shapes and dynamics of a chain spun about the vertical axis.
# Targets: all (default), demo, check, check-clang, check-sanitize, bench, study, python, deps,
# clean.
# BUILD=dir builds out of tree (several builds can coexist).

BUILD    ?= build
CC       ?= cc
PKGS     := gsl nlopt inih lapacke
OPT      ?= -O2
PYTHON   ?= /usr/bin/python3
CFLAGS   ?= $(OPT) -g
# -Wno-missing-field-initializers: option tables (src/cli/cli.h) leave trailing fields out on
# purpose; they are zero, which means "not used".
WFLAGS   := -std=c11 -Wall -Wextra -Wpedantic -Wshadow -Wno-unused-parameter \
            -Wno-missing-field-initializers
CPPFLAGS := -Iinclude -Isrc -D_POSIX_C_SOURCE=200809L -MMD -MP
# The version, from include/whirl/version.h; the shared library's SONAME carries MAJOR.
version_part = $(shell awk '$$2 == "WHIRL_VERSION_$(1)" { print $$3 }' include/whirl/version.h)
MAJOR    := $(call version_part,MAJOR)
VERSION  := $(MAJOR).$(call version_part,MINOR).$(call version_part,PATCH)
PKG_CFLAGS = $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
PKG_LIBS   = $(shell pkg-config --libs $(PKGS) 2>/dev/null)
LDLIBS    = $(PKG_LIBS) -llapack -lblas -lpthread -lm
ALL_CFLAGS = $(WFLAGS) $(CFLAGS) -fopenmp $(PKG_CFLAGS) $(XCFLAGS)
ALL_LDFLAGS = -fopenmp $(LDFLAGS) $(XLDFLAGS)

LIB_SRC  := $(wildcard src/*.c)
CLI_SRC  := $(wildcard src/cli/*.c)
TEST_SRC := $(wildcard tests/test_*.c)
BENCH_SRC := $(wildcard tests/bench_*.c)
LIB_OBJ  := $(LIB_SRC:%.c=$(BUILD)/%.o)
CLI_OBJ  := $(CLI_SRC:%.c=$(BUILD)/%.o)
TEST_BIN := $(TEST_SRC:tests/%.c=$(BUILD)/tests/%)
BENCH_BIN := $(BENCH_SRC:tests/%.c=$(BUILD)/tests/%)
# fuzz harnesses (tests/fuzz/fuzz_NAME.c): replay_NAME runs files through one in `make check`
FUZZ_SRC := $(wildcard tests/fuzz/fuzz_*.c)
FUZZ_NAMES := $(FUZZ_SRC:tests/fuzz/fuzz_%.c=%)
FUZZ_CLI_OBJ = $(addprefix $(BUILD)/src/cli/,cli.o points_csv.o cmd_simulate.o)
REPLAY_BIN := $(FUZZ_NAMES:%=$(BUILD)/tests/fuzz/replay_%)

SHLIB    := $(BUILD)/libwhirl.so.$(VERSION)

.PHONY: all objects demo check check-clang check-sanitize bench study python deps clean fuzz \
  install uninstall
all: $(BUILD)/whirl $(BUILD)/libwhirl.a $(SHLIB) $(BUILD)/whirl.1

$(BUILD)/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(ALL_CFLAGS) $(LIB_FLAGS) -c $< -o $@

# Objects are rebuilt when the compiler or its flags change (recorded in $(BUILD)/flags).
FLAGS_NOW := $(CC) $(CPPFLAGS) $(ALL_CFLAGS)
ifneq ($(MAKECMDGOALS),clean)
$(shell mkdir -p $(BUILD) && echo '$(FLAGS_NOW)' | cmp -s - $(BUILD)/flags || echo '$(FLAGS_NOW)' >$(BUILD)/flags)
endif
$(LIB_OBJ) $(CLI_OBJ): $(BUILD)/flags

# The library's objects serve the static and the shared library: position independent, and only
# the functions marked WHIRL_API (include/whirl/common.h) visible outside the shared library.
$(LIB_OBJ): LIB_FLAGS := -fPIC -fvisibility=hidden

$(BUILD)/libwhirl.a: $(LIB_OBJ)
	@mkdir -p $(dir $@)
	rm -f $@
	$(AR) rcs $@ $^

$(SHLIB): $(LIB_OBJ)
	$(CC) -shared -Wl,-soname,libwhirl.so.$(MAJOR) -Wl,--no-undefined $(ALL_LDFLAGS) $^ \
	  $(LDLIBS) -o $@
	ln -sf libwhirl.so.$(VERSION) $(BUILD)/libwhirl.so.$(MAJOR)
	ln -sf libwhirl.so.$(MAJOR) $(BUILD)/libwhirl.so

# The unversioned name, for the linker's -lwhirl and the Python package (python/).
$(BUILD)/libwhirl.so: $(SHLIB)
	ln -sf libwhirl.so.$(MAJOR) $@

# The manual page, generated from the program's --help (scripts/man.sh).
$(BUILD)/whirl.1: $(BUILD)/whirl scripts/man.sh
	sh scripts/man.sh $(BUILD)/whirl >$@.tmp && mv $@.tmp $@

# make install PREFIX=/usr/local DESTDIR=: the program, libwhirl.a and libwhirl.so, the headers,
# whirl.pc for pkg-config, the manual page. make uninstall removes them.
PREFIX     ?= /usr/local
BINDIR     ?= $(PREFIX)/bin
LIBDIR     ?= $(PREFIX)/lib
INCLUDEDIR ?= $(PREFIX)/include
MANDIR     ?= $(PREFIX)/share/man
PKGCONFIGDIR ?= $(LIBDIR)/pkgconfig
INSTALL_VARS = BUILD='$(BUILD)' VERSION='$(VERSION)' MAJOR='$(MAJOR)' DESTDIR='$(DESTDIR)' \
  PREFIX='$(PREFIX)' BINDIR='$(BINDIR)' LIBDIR='$(LIBDIR)' INCLUDEDIR='$(INCLUDEDIR)' \
  MANDIR='$(MANDIR)' PKGCONFIGDIR='$(PKGCONFIGDIR)'
install: all
	@$(INSTALL_VARS) sh scripts/install.sh install
uninstall:
	@$(INSTALL_VARS) sh scripts/install.sh uninstall

$(BUILD)/whirl: $(CLI_OBJ) $(BUILD)/libwhirl.a
	$(CC) $(ALL_LDFLAGS) $(CLI_OBJ) $(BUILD)/libwhirl.a $(LDLIBS) -o $@

# --- MPI (Open MPI): with mpicc present, `whirl regime` shares a map out over the ranks of
# `mpirun -n K`; `make MPI=0` builds the single-process program without MPI.
MPI ?= $(if $(shell command -v mpicc 2>/dev/null),1,0)
ifeq ($(MPI),1)
$(BUILD)/src/cli/cmd_regime.o: PKG_CFLAGS += -DWHIRL_MPI $(shell mpicc --showme:compile)
$(BUILD)/whirl: PKG_LIBS += $(shell mpicc --showme:link)
endif
# --- end MPI

$(BUILD)/tests/%: tests/%.c $(BUILD)/libwhirl.a
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(ALL_CFLAGS) $< $(BUILD)/libwhirl.a $(ALL_LDFLAGS) $(LDLIBS) -lcmocka -o $@

$(BUILD)/tests/fuzz/replay_%: tests/fuzz/fuzz_%.c tests/fuzz/replay.c $(FUZZ_CLI_OBJ) $(BUILD)/libwhirl.a
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) -Itests/fuzz $(ALL_CFLAGS) $< tests/fuzz/replay.c $(FUZZ_CLI_OBJ) \
	  $(BUILD)/libwhirl.a $(ALL_LDFLAGS) $(LDLIBS) -o $@

# libFuzzer campaigns (clang, ASan, UBSan), FUZZ_TIME seconds per harness: new inputs go to
# out/fuzz/NAME, crashes to out/fuzz/artifacts; the committed corpus tests/fuzz/corpus/NAME seeds
# them. See tests/fuzz/README.md.
FUZZ_TIME ?= 60
FUZZ_FLAGS := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
fuzz: deps
	@$(MAKE) --no-print-directory BUILD=build-fuzz CC=clang OPT=-O1 MPI=0 \
	  XCFLAGS="$(FUZZ_FLAGS) -fsanitize=fuzzer-no-link" XLDFLAGS="$(FUZZ_FLAGS)" \
	  build-fuzz/libwhirl.a $(FUZZ_CLI_OBJ:$(BUILD)/%=build-fuzz/%)
	@mkdir -p out/fuzz/artifacts
	@for f in $(FUZZ_NAMES); do \
	  clang $(CPPFLAGS) -Itests/fuzz $(WFLAGS) -O1 -g -fopenmp $(PKG_CFLAGS) $(FUZZ_FLAGS) \
	    -fsanitize=fuzzer tests/fuzz/fuzz_$$f.c $(FUZZ_CLI_OBJ:$(BUILD)/%=build-fuzz/%) \
	    build-fuzz/libwhirl.a $(LDLIBS) -o build-fuzz/fuzz_$$f || exit 1; \
	  mkdir -p out/fuzz/$$f; \
	  echo "fuzz_$$f: $(FUZZ_TIME) s"; \
	  build-fuzz/fuzz_$$f -max_total_time=$(FUZZ_TIME) -timeout=10 -rss_limit_mb=2048 \
	    -dict=tests/fuzz/$$f.dict -artifact_prefix=out/fuzz/artifacts/$$f- -print_final_stats=1 \
	    out/fuzz/$$f tests/fuzz/corpus/$$f >out/fuzz/$$f.log 2>&1; rc=$$?; \
	  grep -E 'INITED|DONE|ERROR|SUMMARY|Test unit written|number_of_executed|new_units' \
	    out/fuzz/$$f.log; [ $$rc -eq 0 ] || exit 1; \
	done

# Debian packages the build, the tests and the figures need; installed when run as root.
deps:
	@sh scripts/deps.sh

demo: deps
	@$(MAKE) --no-print-directory all
	@sh scripts/demo.sh $(BUILD)

# The tests and the installed library's (tests/install.sh: a temporary prefix, the examples built
# with pkg-config), a clang -Werror compile of the library and the program, then the same tests
# under AddressSanitizer and UndefinedBehaviorSanitizer.
check: deps
	@$(MAKE) --no-print-directory all $(TEST_BIN) $(REPLAY_BIN)
	@sh tests/run.sh $(BUILD) --also tests/install.sh
	@$(MAKE) --no-print-directory check-clang
	@$(MAKE) --no-print-directory check-sanitize

# The library and the program compiled (not linked) by clang with warnings as errors.
check-clang: deps
	@$(MAKE) --no-print-directory BUILD=build-clang CC=clang XCFLAGS=-Werror objects
	@echo "clang -Werror: library and program compile cleanly"

objects: $(LIB_OBJ) $(CLI_OBJ)
	@:

check-sanitize: deps
	@$(MAKE) --no-print-directory BUILD=build-sanitize OPT=-O1 \
	  XCFLAGS="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined" \
	  XLDFLAGS="-fsanitize=address,undefined" all \
	  $(TEST_BIN:$(BUILD)/%=build-sanitize/%) $(REPLAY_BIN:$(BUILD)/%=build-sanitize/%)
	@WHIRL_SANITIZE=1 sh tests/run.sh build-sanitize

bench: deps
	@$(MAKE) --no-print-directory all $(BENCH_BIN) $(BUILD)/libwhirl.so
	@sh scripts/bench.sh $(BUILD)

# The studies behind the figures: stability maps and the regime map (several minutes).
study: deps
	@$(MAKE) --no-print-directory all
	@sh scripts/study.sh all out/study $(BUILD)

# The Python package (python/) with the shared library copied into it, installed by pip without
# network access. As root on Debian pip installs into /usr/local/lib/python3.*/dist-packages,
# apart from apt's packages, once told to (--break-system-packages: Debian marks its Python as
# managed by apt). Inside a venv: make python PYTHON=venv/bin/python PIP_FLAGS=
PIP_FLAGS ?= --break-system-packages
python: deps
	@$(MAKE) --no-print-directory $(BUILD)/libwhirl.so
	cp $(BUILD)/libwhirl.so python/whirl/libwhirl.so
	$(PYTHON) -m pip install --no-build-isolation --no-deps --no-index $(PIP_FLAGS) ./python

clean:
	rm -rf build build-* out

-include $(LIB_OBJ:.o=.d) $(CLI_OBJ:.o=.d) $(TEST_BIN:=.d) $(BENCH_BIN:=.d)
