# Strand: `make run` (set-up, build, demo into out/) and `make test` (set-up, build, all tests).
# As root, missing Debian packages are installed with apt-get; otherwise they are listed.

DEBIAN_PACKAGES := cmake make g++ pkg-config libeigen3-dev nlohmann-json3-dev libcli11-dev \
                   libgtest-dev libbenchmark-dev libpugixml-dev libpolyclipping-dev libtbb-dev \
                   libcairo2-dev libtinygltf-dev python3 libhersheyfont-dev hershey-fonts-data \
                   libfreetype-dev libfontconfig-dev fonts-dejavu-core libpotrace-dev libstb-dev \
                   libnetpbm-dev libcgal-dev libopenmesh-dev lib3mf-dev libzip-dev \
                   libcpp-httplib-dev libsqlite3-dev pybind11-dev python3-dev python3-pybind11 \
                   python3-numpy libopencv-dev
MAKEFLAGS += --no-print-directory
BUILD_DIR := build
STRAND := $(BUILD_DIR)/cli/strand
CMAKE_FLAGS := -DCMAKE_BUILD_TYPE=Release $(if $(CI),-DSTRAND_WERROR=ON,)

# Sanitizer and fuzzing build (clang): ASan + UBSan over the whole test suite, libFuzzer targets.
SANITIZE_PACKAGES := clang libclang-rt-14-dev lld
SAN_DIR := build-asan
# -O1 and line tables: what the sanitizers need for speed and file:line stack traces, at about
# half the compile and link time of -O2 -g (NDEBUG as RelWithDebInfo has it).
SAN_FLAGS := -O1 -gline-tables-only -DNDEBUG
FUZZ_SECONDS ?= 600

.PHONY: all deps web-deps configure build build-strand build-tests python install run test bench bench-micro clean sanitize fuzz fuzz-ci sanitize-build

all: build

deps:
	@missing=""; \
	for p in $(DEBIAN_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = "0" ]; then \
	    echo "installing Debian packages:$$missing"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $$missing >/dev/null; \
	  else \
	    echo "missing Debian packages:$$missing -- run 'sudo apt-get install$$missing' or run make as root"; exit 1; \
	  fi; \
	fi

# The viewer's browser libraries (three.js, esbuild to bundle them into the binary), pinned in
# web/package-lock.json: `npm ci` when web/node_modules is missing or older than the lock file;
# Debian's npm only when there is no npm at all.
web-deps:
	@if [ ! -f web/node_modules/.package-lock.json ] || [ web/package-lock.json -nt web/node_modules/.package-lock.json ]; then \
	  if ! command -v npm >/dev/null; then \
	    if [ "$$(id -u)" = "0" ]; then apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends nodejs npm >/dev/null; \
	    else echo "npm is missing -- run 'sudo apt-get install nodejs npm' or run make as root"; exit 1; fi; \
	  fi; \
	  cd web && npm ci --ignore-scripts --no-audit --no-fund --loglevel=error; \
	fi

configure: deps web-deps
	@cmake -S . -B $(BUILD_DIR) $(CMAKE_FLAGS) >/dev/null

# Everything: the program, the test executable and the benchmarks.
build: configure
	@cmake --build $(BUILD_DIR) -j$$(nproc)

# The demo needs the strand program only (tests and benchmarks are built by `make test` and
# `make bench`).
build-strand: configure
	@cmake --build $(BUILD_DIR) -j$$(nproc) --target strand

# The Python module alone: build/python/strand (PYTHONPATH=build/python; docs/python.md).
python: configure
	@cmake --build $(BUILD_DIR) -j$$(nproc) --target strand_python

run: build-strand
	@./samples/run_demo.sh $(STRAND) out
	@echo "the workbench (design, preview, gallery in a browser): $(STRAND) serve, then open http://127.0.0.1:8080/"

# bin/strand, share/strand/machines, share/man/man1 (strand.1 and one page per command),
# bash and zsh completion, share/doc/strand, and the Python module in
# lib/python3.X/dist-packages/strand. `make install PREFIX=~/.local` needs no root.
PREFIX ?= /usr/local
install: build-strand
	@if [ -d $(BUILD_DIR)/python ]; then cmake --build $(BUILD_DIR) -j$$(nproc) --target strand_python; fi
	@cmake --install $(BUILD_DIR) --prefix "$(PREFIX)"

# Test-only tools: javac/java compile and run the generated Sunrise programs against stand-in
# classes (tests/machines/sunrise_writer_test.cpp); Chromium loads the HTML previews headless;
# groff checks the manual pages; pytest, nbconvert (with the kernel, matplotlib and pandas the
# notebooks use) run the Python module's tests and examples/*.ipynb.
TEST_PACKAGES := openjdk-17-jdk-headless chromium chromium-driver python3-selenium groff-base curl \
                 python3-pytest jupyter-nbconvert python3-ipykernel python3-matplotlib python3-pandas
# A single-node Slurm started by tests/jobs/slurm_cluster_test.cpp (strand sweep --slurm).
TEST_PACKAGES += slurm-wlm munge

# What the tests run (the program, the test executable, the Python module); the benchmarks are
# left to `make bench`.
build-tests: configure
	@cmake --build $(BUILD_DIR) -j$$(nproc) --target strand strand_tests \
	  $$(test -d $(BUILD_DIR)/python && echo strand_python)

test: build-tests
	@$(MAKE) deps DEBIAN_PACKAGES="$(TEST_PACKAGES)"
	@cd $(BUILD_DIR) && ctest --output-on-failure -j$$(nproc)

# One table of the issue-13 figures (cpu, memory per move/stroke, pen-up travel, check and
# sweep times) from the strand program, then the 3D viewer on a million moves (issue 34);
# bench-micro runs the Google Benchmark programs.
bench: build
	@python3 tests/bench/bench_table.py $(STRAND)
	@python3 tests/bench/view_bench.py $(STRAND)

bench-micro: build
	@$(BUILD_DIR)/tests/bench/strand_bench

sanitize-build: deps web-deps
	@$(MAKE) deps DEBIAN_PACKAGES="$(SANITIZE_PACKAGES)"
	@cmake -S . -B $(SAN_DIR) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
	  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$(SAN_FLAGS)" -DCMAKE_EXE_LINKER_FLAGS=-fuse-ld=lld \
	  -DSTRAND_SANITIZE=ON -DSTRAND_FUZZ=ON >/dev/null
	@cmake --build $(SAN_DIR) -j$$(nproc)

# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer (any report fails it; the
# code under test is instrumented, the test files are not: tests/CMakeLists.txt), one
# process per core (tests/sanitize_run.sh), but for the cases tests/sanitize_skip.txt lists with
# the reason: end-to-end and property cases, 8-30x slower here, whose code lighter cases already
# run under the sanitizers.
sanitize: sanitize-build
	@$(MAKE) deps DEBIAN_PACKAGES="$(TEST_PACKAGES)"
	@tests/sanitize_run.sh $(SAN_DIR)

# Each fuzz target for FUZZ_SECONDS (default 600), two at a time on two cores; fuzz-ci is the
# short run in .ci/run: a fixed seed, a fresh corpus and a fixed number of executions per target
# (tests/fuzz/run_fuzzers.sh, ci_runs: about 30 s each), so CI replays exactly the inputs a
# local `make fuzz-ci` tried (a random run could fail CI on a finding nobody saw).
FUZZ_SEED ?=
FUZZ_RUNS ?=
fuzz: sanitize-build
	@LSAN_OPTIONS=suppressions=$(CURDIR)/tests/fuzz/lsan.supp:print_suppressions=0 \
	  FUZZ_SEED=$(FUZZ_SEED) FUZZ_RUNS=$(FUZZ_RUNS) tests/fuzz/run_fuzzers.sh $(SAN_DIR) $(FUZZ_SECONDS)

fuzz-ci:
	@$(MAKE) fuzz FUZZ_SECONDS=600 FUZZ_SEED=1 FUZZ_RUNS=ci

clean:
	rm -rf $(BUILD_DIR) $(SAN_DIR) out
