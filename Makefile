# SPDX-License-Identifier: GPL-3.0-or-later
# qusgm: quasi-static granular mechanics toolkit.
# Targets: all check run bench bench-peers validate install uninstall deb clean deps help (see `make help`).

VERSION   = 0.2.0
PREFIX   ?= /usr/local
BINDIR   ?= $(PREFIX)/bin
MANPREFIX ?= $(PREFIX)/share/man
DATADIR  ?= $(PREFIX)/share/qusgm
LIBDIR   ?= $(PREFIX)/lib
INCLUDEDIR ?= $(PREFIX)/include
PKGCONFIGDIR ?= $(LIBDIR)/pkgconfig
# The Python package (share/python/qusgm) goes where PYTHON finds it for PREFIX
# (share/python/pythondir.py): Debian's /usr/lib/python3/dist-packages for PREFIX=/usr,
# /usr/local/lib/python3.X/dist-packages for /usr/local; Debian's python3 by default.
PYTHON   ?= $(firstword $(wildcard /usr/bin/python3) python3)
PYTHONDIR ?= $(shell $(PYTHON) share/python/pythondir.py $(PREFIX))
DESTDIR  ?=

CC       ?= cc
OPT      ?= -O2 -g
# CFLAGS replaces OPT (the optimisation and debug flags; the warnings, -std, OpenMP and -Ilib
# are always added), CPPFLAGS and LDFLAGS are added to every compile and link: the
# conventions dpkg-buildflags and other packagers follow (make deb).  Unset, the commands
# are those of OPT alone.
CFLAGS   ?= $(OPT)
WARN      = -Wall -Wextra -Wshadow -Wstrict-prototypes -Wmissing-prototypes
# -ffp-contract=off: no fused multiply-adds the source does not write (GCC's ISO C mode already
# implies it, clang's default does not), so the bytes do not depend on the compiler's choice
# and a lane computes what its scalar code does (lib/base/lanes.h)
STD       = -std=c11 -ffp-contract=off -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE
PKGS      = gsl ccd zlib
# The shared library: libqusgm.so.$(VERSION), soname libqusgm.so.$(SOMAJOR).  Version 0: no
# ABI stability promised yet (share/doc/library.md, "Using the library").
SOMAJOR   = 0
SONAME    = libqusgm.so.$(SOMAJOR)
SOLIB     = libqusgm.so.$(VERSION)
DEB_PKGS  = libgsl-dev libccd-dev zlib1g-dev pkg-config libjs-three
# packview inlines three.js from Debian's libjs-three when it runs (tools/packview.c)
THREE_JS  = /usr/share/javascript/three/three.min.js
# packview's browser test opens its pages in headless Chromium (tests/tools/packview.sh)
DEB_BROWSER = chromium
DEB_PLOT  = gnuplot-nox
DEB_PY    = python3-numpy python3-pandas python3-setuptools
DEB_PEERS = liggghts

# The exact source of a build, which every tool's --version and every history line it writes
# name (lib/base/cli.c): VERSION, then from a git checkout "+" and what `git describe --always
# --dirty` prints (0.2.0+<hash>, 0.2.0+<hash>-dirty with uncommitted changes); outside git (a
# tarball) VERSION alone.  The -dirty mark comes from git status, which reads as describe's
# does but takes no lock on the index (GIT_OPTIONAL_LOCKS=0), so that a build never blocks a
# commit in the same tree.  Computed once per make and exported to the sub-makes and the
# tests, so that every build of one make names the same source; QUSGM_SOURCE_VERSION=... on
# the command line sets it.
ifeq ($(origin QUSGM_SOURCE_VERSION),undefined)
GIT_DESCRIBE := $(if $(wildcard .git),$(shell d=$$(git describe --always 2>/dev/null) && \
  { [ -z "$$(GIT_OPTIONAL_LOCKS=0 git status --porcelain --untracked-files=no 2>/dev/null)" ] || d=$$d-dirty; } && \
  echo "$$d"))
QUSGM_SOURCE_VERSION := $(VERSION)$(if $(GIT_DESCRIBE),+$(GIT_DESCRIBE))
endif
export QUSGM_SOURCE_VERSION

# Build directories: build/ is the normal build, build-san/ the sanitizer build.
B        ?= build
SANFLAGS  = -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all

PKG_CFLAGS := $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
PKG_LIBS   := $(shell pkg-config --libs $(PKGS) 2>/dev/null)
ifeq ($(strip $(PKG_LIBS)),)
PKG_LIBS := -lgsl -lgslcblas -lccd -lz
endif

# OpenMP: the evaluations and the vector algebra run on threads (lib/base/par.h); OMPFLAGS=
# builds without them (one thread, the same results).
OMPFLAGS ?= -fopenmp
# QUSGM_BUILD: what make compiles sees the library's internal inline code in the headers that
# the installed API includes for their types (lanes.h's SIMD twins in law.h and layout.h); a
# user's program, without it, does not (tests/tools/install.sh compiles it -pedantic)
ALL_CFLAGS = $(STD) $(CPPFLAGS) $(WARN) $(CFLAGS) $(OMPFLAGS) $(EXTRA_CFLAGS) -DQUSGM_BUILD -Ilib $(PKG_CFLAGS)
# GCC's libgomp, linked into each tool (libgomp.a; the shared one is then not needed): it
# reads OMP_WAIT_POLICY in a constructor, which lib/base/par_start.c's runs before only when
# both are in the tool (lib/base/par.h, "Waits").  Empty with clang (libomp reads its
# environment later) or where GCC has no libgomp.a; OMP_STATIC= links the shared libgomp,
# whose idle threads then spin unless OMP_WAIT_POLICY or GOMP_SPINCOUNT is set.
OMP_STATIC ?= $(if $(OMPFLAGS),$(shell $(CC) -dM -E -x c /dev/null 2>/dev/null | grep -q __clang__ || \
  { p=$$($(CC) -print-file-name=libgomp.a 2>/dev/null) && [ -f "$$p" ] && echo "$$p -ldl -Wl,--as-needed"; }))
ALL_LIBS   = $(PKG_LIBS) -lm

# lib/base/par_start.c sets the tools' wait policy for idle threads: linked into the tools
# alone (TOOL_START), not into the library, which leaves its program's environment alone
TOOL_START_SRC = lib/base/par_start.c
LIB_SRC   = $(filter-out $(TOOL_START_SRC),$(wildcard lib/*/*.c))
# packview's page template (lib/analysis/view_page.html), compiled in as a C string
GEN_SRC   = analysis/view_page
LIB_OBJ   = $(LIB_SRC:lib/%.c=$(B)/lib/%.o) $(GEN_SRC:%=$(B)/lib/%.o)
PIC_OBJ   = $(LIB_SRC:lib/%.c=$(B)/pic/%.o) $(GEN_SRC:%=$(B)/pic/%.o)
LIB_HDR   = $(wildcard lib/*/*.h)
TOOL_SRC  = $(wildcard tools/*.c)
TOOLS     = $(TOOL_SRC:tools/%.c=%)
TOOL_BIN  = $(TOOLS:%=$(B)/bin/%)
TOOL_START = $(TOOL_START_SRC:lib/%.c=$(B)/lib/%.o)
UNIT_SRC  = $(wildcard tests/unit/*.c)
UNIT_BIN  = $(UNIT_SRC:tests/unit/%.c=$(B)/tests/%)
BENCH_SRC = $(wildcard tests/bench/*.c)
BENCH_BIN = $(BENCH_SRC:tests/bench/%.c=$(B)/bench/%)
FUZZ_SRC  = $(wildcard tests/fuzz/fuzz_*.c)
FUZZ      = $(FUZZ_SRC:tests/fuzz/%.c=%)
FUZZ_REPLAY = $(FUZZ:%=$(B)/tests/replay_%)
MAN1      = $(wildcard share/man/man1/*.1)
MAN5      = $(wildcard share/man/man5/*.5)
MAN7      = $(wildcard share/man/man7/*.7)

.PHONY: version FORCE libs all deps deb debdeps browserdeps plotdeps pydeps pipelines check check-fast killtest run bench bench-plates bench-memory bench-1e6 bench-peers validate cluster-check interop install uninstall man-tables clean help tools unit fuzz fuzzdeps fuzz-build
.DELETE_ON_ERROR:

all: deps
	@$(MAKE) --no-print-directory tools unit libs

tools: $(TOOL_START) $(TOOL_BIN)
# The installable library, static and shared (the tools link the static one, as compiled).
libs: $(B)/libqusgm.a $(B)/$(SOLIB) $(B)/api/libqusgm.a $(B)/api/rename.sed
unit: $(UNIT_BIN) $(FUZZ_REPLAY)

# The dependencies come from Debian packages.  As root, install what is missing; otherwise
# stop with the exact command to type.
deps:
	@missing=""; \
	command -v pkg-config >/dev/null 2>&1 || missing="pkg-config"; \
	for m in $(PKGS); do \
	  pkg-config --exists $$m 2>/dev/null || missing="$$missing $$m"; \
	done; \
	[ -f $(THREE_JS) ] || missing="$$missing libjs-three"; \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	    echo "qusgm: installing missing build dependencies ($$missing)"; \
	    { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $(DEB_PKGS); } >/dev/null || \
	      { echo "qusgm: apt-get install failed; run: apt-get install $(DEB_PKGS)" >&2; exit 1; }; \
	  else \
	    echo "qusgm: missing build dependencies ($$missing); run: sudo apt-get install $(DEB_PKGS)" >&2; exit 1; \
	  fi; \
	fi

$(B)/lib/%.o: lib/%.c $(LIB_HDR)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -c -o $@ $<

# A text file as a C string: each line quoted, with \ " and ? escaped (no trigraphs)
$(B)/gen/%.c: lib/%.html
	@mkdir -p $(@D)
	{ echo '#include "analysis/view.h"'; echo 'const char $(notdir $*)_html[] ='; \
	  sed -e 's/\\/\\\\/g' -e 's/"/\\"/g' -e 's/?/\\?/g' -e 's/^/"/' -e 's/$$/\\n"/' $<; echo ';'; } >$@.tmp && mv $@.tmp $@
$(B)/lib/analysis/view_page.o: $(B)/gen/analysis/view_page.c $(LIB_HDR)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -c -o $@ $<
$(B)/pic/analysis/view_page.o: $(B)/gen/analysis/view_page.c $(LIB_HDR)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -fPIC -c -o $@ $<

# The source version reaches cli.c alone, as a define; its objects depend on a file that
# changes only when the string does, so a new commit or a first edit recompiles one file and
# relinks, nothing more.
$(B)/source-version: FORCE
	@mkdir -p $(@D)
	@echo '$(QUSGM_SOURCE_VERSION)' >$@.$$$$; \
	if cmp -s $@.$$$$ $@; then rm -f $@.$$$$; else mv -f $@.$$$$ $@; fi
$(B)/lib/base/cli.o $(B)/pic/base/cli.o: $(B)/source-version
$(B)/lib/base/cli.o $(B)/pic/base/cli.o: ALL_CFLAGS += -DQUSGM_SOURCE_VERSION='"$(QUSGM_SOURCE_VERSION)"'
FORCE:

$(B)/libqusgm.a: $(LIB_OBJ)
	rm -f $@
	ar rcs $@ $^

# The shared library's objects: a second set, position-independent, so that the tools keep
# the static objects (no PIC in their hot loops).
$(B)/pic/%.o: lib/%.c $(LIB_HDR)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) -fPIC -c -o $@ $<

# The installed libraries export the API alone (lib/qusgm.api), each name prefixed qusgm_: the
# objects linked into one (-r), the API's names renamed and kept global, every other symbol made
# local, so that a program's own table_read or path_parse never meets the library's.  The
# installed headers are the closure of the umbrella lib/qusgm.h, the API's names renamed the
# same way (share/doc/library.md, "Using the library").
OBJCOPY  ?= objcopy
API       = lib/qusgm.api
$(B)/api/names: $(API)
	@mkdir -p $(@D)
	sed -e 's/#.*//' -e '/^[[:space:]]*$$/d' $(API) >$@
$(B)/api/rename.sed: $(B)/api/names
	sed 's/.*/s\/\\<&\\>\/qusgm_\&\/g/' $(B)/api/names >$@
define api_object
$(CC) -r -nostdlib -o $@.all $(filter %.o,$^)
sed 's/.*/& qusgm_&/' $(B)/api/names >$@.redefine
sed 's/^/qusgm_/' $(B)/api/names >$@.keep
$(OBJCOPY) --redefine-syms=$@.redefine --keep-global-symbols=$@.keep $@.all $@
rm -f $@.all $@.redefine $@.keep
endef
$(B)/api/static.o: $(LIB_OBJ) $(B)/api/names
	$(api_object)
$(B)/api/shared.o: $(PIC_OBJ) $(B)/api/names
	$(api_object)
$(B)/api/libqusgm.a: $(B)/api/static.o
	rm -f $@
	ar rcs $@ $^

$(B)/$(SOLIB): $(B)/api/shared.o
	$(CC) $(ALL_CFLAGS) $(LDFLAGS) -shared -Wl,-soname,$(SONAME) -o $@ $^ $(ALL_LIBS)

$(B)/bin/%: tools/%.c $(TOOL_START) $(B)/libqusgm.a $(LIB_HDR)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) $(LDFLAGS) -o $@ $< $(TOOL_START) $(B)/libqusgm.a $(ALL_LIBS) $(OMP_STATIC)

$(B)/tests/%: tests/unit/%.c tests/unit/*.h $(B)/libqusgm.a $(LIB_HDR)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) $(LDFLAGS) -Itests/unit -o $@ $< $(B)/libqusgm.a $(ALL_LIBS)

# The fuzz harnesses (tests/fuzz/) replayed on their seed corpora and crash reproducers with
# the normal compiler: a unit test of each build, one PASS line per directory.
$(B)/tests/replay_%: tests/fuzz/%.c tests/fuzz/replay.c tests/fuzz/*.h $(B)/libqusgm.a $(LIB_HDR)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) $(LDFLAGS) -DFUZZ_NAME=\"$*\" -DFUZZ_CORPUS=\"$(CURDIR)/tests/fuzz/corpus\" \
	  -DFUZZ_CRASHES=\"$(CURDIR)/tests/fuzz/crashes\" -o $@ tests/fuzz/replay.c $< $(B)/libqusgm.a $(ALL_LIBS)

$(B)/bench/%: tests/bench/%.c tests/bench/bench.h tests/unit/plate_place.h $(B)/libqusgm.a $(LIB_HDR)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) $(LDFLAGS) -o $@ $< $(B)/libqusgm.a $(ALL_LIBS)

# packview's browser test needs Chromium (Debian chromium): installed as root when missing,
# else the test fails and says what to install.
browserdeps:
	@if ! command -v chromium >/dev/null 2>&1; then \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	    echo "qusgm: installing $(DEB_BROWSER) for packview's browser test" >&2; \
	    { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $(DEB_BROWSER); } >/dev/null || \
	      echo "qusgm: apt-get install $(DEB_BROWSER) failed: packview's browser test will fail" >&2; \
	  else \
	    echo "qusgm: chromium not found, packview's browser test will fail; run: sudo apt-get install $(DEB_BROWSER)" >&2; \
	  fi; \
	fi

# Figures need gnuplot (Debian gnuplot-nox): installed as root, else the exact command.
plotdeps:
	@if ! command -v gnuplot >/dev/null 2>&1; then \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	    echo "qusgm: installing $(DEB_PLOT) for figures" >&2; \
	    DEBIAN_FRONTEND=noninteractive apt-get install -y $(DEB_PLOT) >/dev/null || \
	      echo "qusgm: apt-get install $(DEB_PLOT) failed: figures will be skipped" >&2; \
	  else \
	    echo "qusgm: gnuplot not found, figures will be skipped; run: sudo apt-get install $(DEB_PLOT)" >&2; \
	  fi; \
	fi

# The Python package's test (tests/tools/python.sh) runs under PYTHON (Debian's python3) and needs
# numpy, pandas (the documented read_csv call, to_dataframe) and setuptools (the wheel): installed
# as root when missing, else the exact command; the test fails without numpy, never skips.
pydeps:
	@if ! $(PYTHON) -c 'import numpy, pandas, setuptools' >/dev/null 2>&1; then \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	    echo "qusgm: installing $(DEB_PY) for the Python package's test" >&2; \
	    { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $(DEB_PY); } >/dev/null || \
	      echo "qusgm: apt-get install $(DEB_PY) failed: the Python test will fail" >&2; \
	  else \
	    echo "qusgm: $(PYTHON) lacks numpy, pandas or setuptools, the Python test will fail; run: sudo apt-get install $(DEB_PY)" >&2; \
	  fi; \
	fi

# make check: the normal build and the sanitizer build, unit tests and tool tests under both,
# then one closing line "N passed, N failed".
# The builds compile on every core (CHECK_JOBS, default the cores online): on CI's two cores a
# fresh clone spends about a minute and a half compiling otherwise.
CHECK_JOBS ?= $(shell getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)
check: deps pydeps browserdeps
	@$(MAKE) --no-print-directory -j$(CHECK_JOBS) B=build tools unit libs
	@$(MAKE) --no-print-directory -j$(CHECK_JOBS) B=build-san OPT="-O1 -g" EXTRA_CFLAGS="$(SANFLAGS)" tools unit
	@sh tests/run.sh build build-san

# Quicker loop while developing: normal build only.
check-fast: all browserdeps
	@sh tests/run.sh build

# Signals at random moments against every tool that writes files (tests/killtest.sh): a minute
# or two and timing-dependent, so not part of make check (tests/tools/signals.sh is, the
# deterministic part).  KILLTEST_SEED and KILLTEST_REPS (default 19 and 3) set the sequence.
killtest: all
	@sh tests/killtest.sh build/bin

# make fuzz [FUZZ_SECONDS=60] [FUZZ_JOBS=NAME...]: each libFuzzer harness in turn for that
# long, on a copy of its seed corpus (tests/fuzz/corpus/NAME, which it does not grow), the
# library built with clang and the sanitizers in build-fuzz/.  Crashes are left in
# build-fuzz/crashes/NAME/.  clang is installed as root when missing.  FUZZ_MAX_LEN_NAME caps
# the inputs of harness NAME (bytes): 256 KB for the pack and table readers, whose real
# inputs are large (a pack of a few thousand grains, a long curve), 8 KB for the others.
FUZZ_SECONDS ?= 60
FUZZ_MAX_LEN_fuzz_pack     ?= 262144
FUZZ_MAX_LEN_fuzz_table    ?= 262144
FUZZ_MAX_LEN_fuzz_material ?= 8192
FUZZ_MAX_LEN_fuzz_psd      ?= 8192
FUZZ_MAX_LEN_fuzz_loadpath ?= 8192
FUZZ_MAX_LEN_DEFAULT       ?= 8192
FUZZ_JOBS    ?= $(FUZZ)
FUZZ_CC       = clang
FUZZ_FLAGS    = -fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all

fuzzdeps:
	@if ! command -v $(FUZZ_CC) >/dev/null 2>&1; then \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	    echo "qusgm: installing clang for make fuzz"; \
	    { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq clang; } >/dev/null || \
	      { echo "qusgm: apt-get install failed; run: apt-get install clang" >&2; exit 1; }; \
	  else \
	    echo "qusgm: clang not found; run: sudo apt-get install clang" >&2; exit 1; \
	  fi; \
	fi

fuzz-build: deps fuzzdeps
	@$(MAKE) --no-print-directory B=build-fuzz CC=$(FUZZ_CC) OPT="-O1 -g" EXTRA_CFLAGS="$(FUZZ_FLAGS)" \
	  $(FUZZ:%=build-fuzz/fuzz/%)

build-fuzz/fuzz/%: tests/fuzz/%.c tests/fuzz/*.h $(B)/libqusgm.a $(LIB_HDR)
	@mkdir -p $(@D)
	$(CC) $(ALL_CFLAGS) $(LDFLAGS) -fsanitize=fuzzer -o $@ $< $(B)/libqusgm.a $(ALL_LIBS)

fuzz: fuzz-build
	@for f in $(FUZZ_JOBS); do \
	  maxlen=$(FUZZ_MAX_LEN_DEFAULT); \
	  for p in $(foreach h,$(FUZZ_JOBS),$(h)=$(or $(FUZZ_MAX_LEN_$(h)),$(FUZZ_MAX_LEN_DEFAULT))); do \
	    [ "$${p%%=*}" = "$$f" ] && maxlen=$${p#*=}; \
	  done; \
	  rm -rf build-fuzz/corpus/$$f; mkdir -p build-fuzz/corpus/$$f build-fuzz/crashes/$$f; \
	  cp tests/fuzz/corpus/$$f/* build-fuzz/corpus/$$f/; \
	  echo "== $$f ($(FUZZ_SECONDS) s, inputs up to $$maxlen bytes)"; \
	  build-fuzz/fuzz/$$f -max_total_time=$(FUZZ_SECONDS) -max_len=$$maxlen -timeout=10 -rss_limit_mb=2048 \
	    -artifact_prefix=build-fuzz/crashes/$$f/ build-fuzz/corpus/$$f 2>build-fuzz/$$f.log || \
	    { tail -n 40 build-fuzz/$$f.log; echo "$$f: crash, reproducer in build-fuzz/crashes/$$f/" >&2; exit 1; }; \
	  grep -E '^#[0-9]+.*(DONE|pulse|NEW)' build-fuzz/$$f.log | tail -n 1; \
	done

run: all plotdeps
	@sh share/run-default.sh build/bin

# The papers' studies (pipelines/README.md): make pipelines [STUDY=fig4] [SMALL=1] [-j2]
STUDY ?= all
pipelines: all plotdeps
	@$(MAKE) --no-print-directory -C pipelines BIN=$(CURDIR)/build/bin $(STUDY)

bench: all
	@$(MAKE) --no-print-directory B=build $(BENCH_SRC:tests/bench/%.c=build/bench/%)
	@sh tests/bench.sh build/bin
	@sh tests/bench-plates.sh build/bin

# The spheroplate DEM alone (bench/plates.md): make bench-plates [BENCH_PLATE_SIZES=1000]
bench-plates: all
	@$(MAKE) --no-print-directory B=build build/bench/platestep
	@sh tests/bench-plates.sh build/bin

# The chain's peak memory at 1.25e6 grains (bench/memory-1e6.md, tests/bench-memory.sh: make
# bench's dense 1e4 pack tiled 5 x 5 x 5, each stage cut short; a few minutes):
# make bench-memory [BENCH_MEMORY_TILES=5]
BENCH_MEMORY_TILES ?= 5
bench-memory: all
	@$(MAKE) --no-print-directory B=build build/bench/evalscale
	@sh tests/bench-memory.sh build/bin $(BENCH_MEMORY_TILES)

# The chain's first stages at 1e6 grains, measured (bench/densify-1e6.md, tests/bench-1e6.sh):
# packgen, densify, one frictional increment; hours, so each call goes on where the last one
# stopped (densify from its checkpoint; with BENCH_1E6_LIMIT=S it stops, exit 75, before S s):
# make bench-1e6 [BENCH_1E6_LIMIT=0 BENCH_1E6_THREADS=2 BENCH_1E6_DIR=bench/1e6]
bench-1e6: all
	@$(MAKE) --no-print-directory B=build build/bench/fincrement
	@sh tests/bench-1e6.sh build/bin build/bench

# qusgm against LIGGGHTS (Hertz-Mindlin DEM) on the same oedometric increments from the same
# pack (bench/peers.md, tests/bench-peers.sh; about a minute): make bench-peers
# [PEERS_INCREMENTS=10].  As root, installs LIGGGHTS if missing; otherwise stops with the
# exact command to type.
bench-peers: all
	@command -v liggghts >/dev/null 2>&1 || \
	if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	  echo "qusgm: installing LIGGGHTS ($(DEB_PEERS))"; \
	  { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq $(DEB_PEERS); } >/dev/null || \
	    { echo "qusgm: apt-get install failed; run: apt-get install $(DEB_PEERS)" >&2; exit 1; }; \
	else \
	  echo "qusgm: make bench-peers needs LIGGGHTS; run: sudo apt-get install $(DEB_PEERS)" >&2; exit 1; \
	fi
	@sh tests/bench-peers.sh build/bin

# Validation against the papers: densify's frictionless compaction (validate/results.md), the
# simple shear of frictional spheres (validate/shear.md), then
# the frictional and polyaxial studies at the papers' sizes, their reports gathered in
# validate/studies.md (pipelines/README.md).
VALIDATE_STUDIES = fig4 fig5-6 fig7 fig8 fig9 s-fig3 s-fig4
validate: all plotdeps
	@sh tests/validate.sh build/bin
	@sh tests/validate-shear.sh build/bin
	@$(MAKE) --no-print-directory -C pipelines BIN=$(CURDIR)/build/bin $(VALIDATE_STUDIES)
	@{ echo "# qusgm validation: the papers' studies"; echo; \
	  echo "Gathered by make validate from pipelines/out/STUDY/report.md ($$(date -u '+%Y-%m-%d %H:%M UTC'), commit $$(git rev-parse --short HEAD 2>/dev/null))."; \
	  for s in $(VALIDATE_STUDIES); do echo; sed 's/^# /## /' pipelines/out/$$s/report.md; done; } >validate/studies.md.tmp && \
	  mv validate/studies.md.tmp validate/studies.md && echo "wrote validate/studies.md"

# A one-node Slurm cluster on this machine (installs slurm-wlm and munge as root; not part of
# make check): a small study with every tool run a job step, compared byte for byte with
# plain make -j (pipelines/README.md "On a Slurm cluster")
cluster-check: all
	@sh tests/cluster-check.sh build/bin

interop: all
	@sh tests/interop.sh build/bin

# The installed headers: lib/qusgm.h and what it includes (its public headers and theirs).
API_HDR   = $(filter lib/%.h,$(shell $(CC) -MM -Ilib $(PKG_CFLAGS) lib/qusgm.h))

# make install copies what make built; it installs no dependency (make does that, as root)
install: tools libs
	mkdir -p $(DESTDIR)$(BINDIR) $(DESTDIR)$(MANPREFIX)/man1 $(DESTDIR)$(MANPREFIX)/man5 $(DESTDIR)$(MANPREFIX)/man7 $(DESTDIR)$(DATADIR)
	cp $(TOOL_BIN) $(DESTDIR)$(BINDIR)/
	cp $(MAN1) $(DESTDIR)$(MANPREFIX)/man1/
	cp $(MAN5) $(DESTDIR)$(MANPREFIX)/man5/
	cp $(MAN7) $(DESTDIR)$(MANPREFIX)/man7/
	cp -R share/doc $(DESTDIR)$(DATADIR)/
	cp README.md NEWS CITATION.cff $(DESTDIR)$(DATADIR)/doc/
	mkdir -p $(DESTDIR)$(DATADIR)/pipelines $(DESTDIR)$(DATADIR)/plot $(DESTDIR)$(DATADIR)/examples
	cp pipelines/Makefile pipelines/README.md pipelines/*.sh $(DESTDIR)$(DATADIR)/pipelines/
	cp share/plot/* $(DESTDIR)$(DATADIR)/plot/
	cp examples/README.md examples/*.sh $(DESTDIR)$(DATADIR)/examples/
	mkdir -p $(DESTDIR)$(PYTHONDIR)/qusgm
	cp share/python/qusgm/__init__.py share/python/qusgm/py.typed $(DESTDIR)$(PYTHONDIR)/qusgm/
	@$(PYTHON) -c 'import sys; sys.exit(sys.argv[1] not in sys.path)' $(PYTHONDIR) || \
	  echo "qusgm: the Python package is in $(PYTHONDIR), where $(PYTHON) does not look: set PYTHONPATH=$(PYTHONDIR) (share/doc/library.md)"
	mkdir -p $(DESTDIR)$(LIBDIR) $(DESTDIR)$(PKGCONFIGDIR)
	cp $(B)/api/libqusgm.a $(B)/$(SOLIB) $(DESTDIR)$(LIBDIR)/
	ln -sf $(SOLIB) $(DESTDIR)$(LIBDIR)/$(SONAME)
	ln -sf $(SONAME) $(DESTDIR)$(LIBDIR)/libqusgm.so
	for h in $(sort $(API_HDR:lib/%=%)); do \
	  mkdir -p $(DESTDIR)$(INCLUDEDIR)/qusgm/$$(dirname $$h) && \
	  sed -f $(B)/api/rename.sed lib/$$h >$(DESTDIR)$(INCLUDEDIR)/qusgm/$$h || exit 1; \
	done
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@LIBDIR@|$(patsubst $(PREFIX)%,$${prefix}%,$(LIBDIR))|' \
	  -e 's|@INCLUDEDIR@|$(patsubst $(PREFIX)%,$${prefix}%,$(INCLUDEDIR))|' -e 's|@VERSION@|$(VERSION)|' \
	  -e 's|@PKGS@|$(PKGS)|' -e 's|@OMPFLAGS@|$(OMPFLAGS)|' share/qusgm.pc.in >$(DESTDIR)$(PKGCONFIGDIR)/qusgm.pc

uninstall:
	for t in $(TOOLS); do rm -f $(DESTDIR)$(BINDIR)/$$t; done
	for m in $(notdir $(MAN1)); do rm -f $(DESTDIR)$(MANPREFIX)/man1/$$m; done
	for m in $(notdir $(MAN5)); do rm -f $(DESTDIR)$(MANPREFIX)/man5/$$m; done
	for m in $(notdir $(MAN7)); do rm -f $(DESTDIR)$(MANPREFIX)/man7/$$m; done
	rm -rf $(DESTDIR)$(DATADIR) $(DESTDIR)$(PYTHONDIR)/qusgm
	rm -f $(DESTDIR)$(LIBDIR)/libqusgm.a $(DESTDIR)$(LIBDIR)/$(SOLIB) $(DESTDIR)$(LIBDIR)/$(SONAME) \
	  $(DESTDIR)$(LIBDIR)/libqusgm.so $(DESTDIR)$(PKGCONFIGDIR)/qusgm.pc
	rm -rf $(DESTDIR)$(INCLUDEDIR)/qusgm

# qusgm-tables(5) is made from share/doc/tables.md, the one description of the tables; the page
# is committed so that installing needs no perl (tests/tools/manpages.sh checks they agree)
man-tables:
	perl share/man/md2man.pl $(VERSION) <share/doc/tables.md >share/man/man5/qusgm-tables.5

# make deb: the Debian packages of debian/ (qusgm, libqusgm0, libqusgm-dev, python3-qusgm),
# built by dpkg-buildpackage -b from a copy of the tree in build-deb/src (it writes them to
# the parent directory: build-deb/), then checked: lintian, with no error allowed, and every
# package unpacked into the scratch root build-deb/root, whose tools must name this tree's
# source and whose Python module must import.  As root, installs the build dependencies
# (deps) and the packaging tools when missing.  The packaged tools name the source of this tree (QUSGM_SOURCE_VERSION).
DEB_TOOLS = dpkg-dev debhelper dh-python lintian
debdeps:
	@missing=""; \
	for p in $(DEB_TOOLS); do \
	  dpkg-query -W -f '$${Status}' $$p 2>/dev/null | grep -q 'ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	    echo "qusgm: installing$$missing for make deb"; \
	    { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq -o DPkg::Lock::Timeout=600 $$missing; } >/dev/null || \
	      { echo "qusgm: apt-get install failed; run: apt-get install$$missing" >&2; exit 1; }; \
	  else \
	    echo "qusgm: make deb needs$$missing; run: sudo apt-get install$$missing" >&2; exit 1; \
	  fi; \
	fi

deb: deps debdeps pydeps
	rm -rf build-deb
	mkdir -p build-deb/src
	if [ -e .git ]; then git ls-files -z | xargs -0 cp -P --parents -t build-deb/src; \
	else tar -cf - --exclude=./.git --exclude='./build*' --exclude=./tests/out . | tar -xf - -C build-deb/src; fi
	@echo "dpkg-buildpackage -us -uc -b (log: build-deb/build.log)"
	@cd build-deb/src && env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL dpkg-buildpackage -us -uc -b >../build.log 2>&1 || \
	  { tail -n 30 ../build.log; echo "qusgm: dpkg-buildpackage failed (build-deb/build.log)" >&2; exit 1; }
	lintian --fail-on error build-deb/*.changes
	for d in build-deb/*.deb; do dpkg -x $$d build-deb/root || exit 1; done
	@for t in $(TOOLS); do \
	  v=$$(LD_LIBRARY_PATH= build-deb/root/usr/bin/$$t --version 2>&1); \
	  case "$$v" in *'$(QUSGM_SOURCE_VERSION)'*) ;; *) echo "qusgm: packaged $$t --version: '$$v', wanted $(QUSGM_SOURCE_VERSION)" >&2; exit 1 ;; esac; \
	done; echo "packaged tools: $(TOOLS) --version name $(QUSGM_SOURCE_VERSION)"
	build-deb/root/usr/bin/packgen -n 50 -q | build-deb/root/usr/bin/packinfo | grep '^grains 50$$'
	@py=$$(command -v /usr/bin/python3 || command -v python3); \
	if $$py -c 'import numpy' 2>/dev/null; then \
	  PYTHONPATH=build-deb/root/usr/lib/python3/dist-packages $$py -c 'import qusgm; print("python3-qusgm: imports from", qusgm.__file__)'; \
	else echo "qusgm: no numpy for $$py: python3-qusgm not imported" >&2; fi
	@ls build-deb/*.deb

clean:
	rm -rf build build-san build-fuzz build-deb tests/out

# The source version this tree builds (QUSGM_SOURCE_VERSION above)
version:
	@echo '$(QUSGM_SOURCE_VERSION)'

help:
	@echo "make            build the library and the tools ($(TOOLS))"
	@echo "make version    the source version the tools name: VERSION, and git describe in a git checkout"
	@echo "make check      build normally and with ASan+UBSan, run every test; ends 'N passed, N failed'"
	@echo "make check-fast the tests on the normal build only"
	@echo "make killtest   kill every writing tool with TERM/INT/HUP/KILL at seeded random moments; check outputs and temporaries"
	@echo "make run        the default job: packgen | densify | frictionalize | loadtest | moduli on G2740 (out/)"
	@echo "make pipelines  the papers' studies (STUDY=name, SMALL=1 for small packs; pipelines/README.md)"
	@echo "make bench      benchmarks; results in bench/results.md and bench/plates.md"
	@echo "make bench-plates  the spheroplate DEM's benchmarks alone (bench/plates.md)"
	@echo "make bench-memory  the chain's peak memory at 1.25e6 grains, tiled (bench/memory-1e6.md)"
	@echo "make bench-1e6     packgen, densify and an increment at 1e6 grains; hours, resumable (bench/densify-1e6.md)"
	@echo "make bench-peers   qusgm against LIGGGHTS on the same oedometric increments (bench/peers.md; installs liggghts as root)"
	@echo "make validate   long validation cases; results in validate/results.md and validate/studies.md"
	@echo "make cluster-check  a one-node Slurm cluster here (root: installs slurm-wlm, munge): a SMALL study through srun vs make -j"
	@echo "make interop    open the exports in third-party readers (needs python3; paraview/ovito if present)"
	@echo "make fuzz       each libFuzzer harness (tests/fuzz/) for FUZZ_SECONDS=$(FUZZ_SECONDS) s, built with clang in build-fuzz/"
	@echo "make install    PREFIX=$(PREFIX) DESTDIR= : tools, man pages, docs, studies, plot scripts, examples, the library (libqusgm.a, $(SOLIB),"
	@echo "                the public headers in include/qusgm, qusgm.pc) and the Python package qusgm in PYTHONDIR"
	@echo "make deb        Debian packages in build-deb/ (debian/; dpkg-buildpackage, lintian; installs the packaging tools as root)"
	@echo "make uninstall  removes what make install installed (same PREFIX and DESTDIR)"
	@echo "knobs: CC OPT (or CFLAGS) CPPFLAGS LDFLAGS EXTRA_CFLAGS PREFIX DESTDIR BINDIR LIBDIR INCLUDEDIR PKGCONFIGDIR MANPREFIX DATADIR PYTHON PYTHONDIR"
