# fricon: the two commands of the README, and a few more for developers.
#   make demo    install what is missing, build (Release), solve the paper's brick
#   make test    install what is missing, build (Release), run the whole CTest suite with the
#                BLAS's default threads, the numerical tests again with one BLAS thread (results
#                must not depend on rounding), then the unit tests and a fast subset of the
#                command-line tests under AddressSanitizer + UndefinedBehaviorSanitizer, in a
#                build without PETSc (which also checks that such a build refuses backend petsc),
#                then builds every fuzz target and runs each for FUZZ_SMOKE_SECONDS (make test-fuzz)
#   make bench   build and run the benchmarks (outside the tests)
#   Both build the Python module into $(BUILD)/python: PYTHONPATH=$(BUILD)/python /usr/bin/python3
#   make format  clang-format every C++ file
BUILD     ?= build
SAN_BUILD ?= build-asan
EXAMPLE   ?= examples/paper-brick.toml
# Warnings are errors in CI (CI=true) and a choice elsewhere.
WERROR    ?= $(if $(filter true,$(CI)),ON,OFF)
# In CI a missing optional dependency (Siconos, PETSc, pytest) is a configure error, not a test
# group lost in silence (cmake/optional_dependencies.cmake).
REQUIRE_OPTIONAL ?= $(if $(filter true,$(CI)),ON,OFF)
CTEST_JOBS ?= 2
# Unity builds (CMake compiles a target's files in batches, each batch one translation unit):
# Eigen's and the project's headers are parsed and their templates instantiated once per batch
# instead of once per file, which halves a clean build (the library in Release on 2 cores: 221 s
# against 408 s). UNITY=OFF for a build where one edited file recompiles alone.
UNITY     ?= ON

.PHONY: deps build demo test test-release test-sanitize test-fuzz bench format clean

deps:
	@bash scripts/install-deps.sh

build: deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DFRICON_WERROR=$(WERROR) \
	  -DFRICON_REQUIRE_OPTIONAL=$(REQUIRE_OPTIONAL) -DCMAKE_UNITY_BUILD=$(UNITY)
	cmake --build $(BUILD)

demo: build
	$(BUILD)/apps/fricon/fricon solve $(EXAMPLE)

test: test-release test-sanitize test-fuzz

# The second pass, with one BLAS thread, leaves out regression.cattaneo_mindlin (a minute and a
# half; the loading path's verification tests run in both passes), and regression.bad_input and
# regression.plots, which check messages and figures rather than numbers that rounding could move.
test-release: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(CTEST_JOBS)
	OPENBLAS_NUM_THREADS=1 ctest --test-dir $(BUILD) --output-on-failure -j $(CTEST_JOBS) \
	  -L "verification|regression" -E "regression.signals|regression.cattaneo_mindlin|regression.bad_input|regression.plots"

# -g1: line tables for the sanitizers' stack traces without the full debug information, which
# halves the compile time of the template-heavy files (the step is most of the clean-clone CI).
test-sanitize: deps
	cmake -S . -B $(SAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-g1 -O1" \
	  -DFRICON_SANITIZE=ON -DFRICON_BUILD_BENCH=OFF -DFRICON_WITH_PETSC=OFF -DFRICON_WERROR=$(WERROR) \
	  -DFRICON_REQUIRE_OPTIONAL=$(REQUIRE_OPTIONAL) -DCMAKE_UNITY_BUILD=$(UNITY)
	cmake --build $(SAN_BUILD)
	ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp \
	  ctest --test-dir $(SAN_BUILD) -L "unit|leak|sanitize" --output-on-failure -j $(CTEST_JOBS)

# BENCH_LARGE=1 adds n = 24, 32, 48 to the contact benchmark (minutes, several GiB), Total FETI's
# scalability to n = 32 with and without the lumped preconditioner, its series against the direct
# solver to n = 48, n = 64 alone and the weak scaling on MPI ranks at n = 24/30 (bench/tfeti_bench.py, two hours), the Hertz
# refinement study with the contact-against-no-contact ratios (bench/hertz_bench.py) and the
# PETSc backend's strong scaling at n = 32, 48 (bench/petsc_scaling.py, docs/parallel.md); the Coulomb
# runs at those sizes: build/bench/contact_bench --model coulomb 24 32 48 (10 min, 14 GiB).
bench: build
	@for b in $(BUILD)/bench/*_bench; do echo "== $$b"; $$b || exit 1; done
	@echo "== $(BUILD)/bench/contact_bench --model coulomb"; $(BUILD)/bench/contact_bench --model coulomb
	@if [ -n "$(BENCH_LARGE)" ]; then $(BUILD)/bench/contact_bench 24 32 48; fi
	@if [ -x $(BUILD)/bench/siconos_compare ]; then echo "== siconos_compare"; $(BUILD)/bench/siconos_compare; fi
	@if [ -x $(BUILD)/bench/fclib_compare ]; then echo "== fclib_compare"; $(BUILD)/bench/fclib_compare; fi
	@if [ -n "$(BENCH_LARGE)" ] && $(BUILD)/apps/fricon/fricon --version | grep -q petsc; then \
	  /usr/bin/python3 bench/petsc_scaling.py $(BUILD)/apps/fricon/fricon; fi
	@echo "== bench/wheel_bench.py"; /usr/bin/python3 bench/wheel_bench.py $(BUILD)/apps/fricon/fricon
	@if [ -n "$(BENCH_LARGE)" ]; then echo "== bench/hertz_bench.py"; \
	  /usr/bin/python3 bench/hertz_bench.py $(BUILD)/apps/fricon/fricon; fi
	@echo "== bench/python_study.py"; PYTHONPATH=$(BUILD)/python /usr/bin/python3 bench/python_study.py \
	  $(BUILD)/apps/fricon/fricon
	@echo "== bench/floating_bench.py"; /usr/bin/python3 bench/floating_bench.py $(BUILD)/apps/fricon/fricon
	@echo "== bench/obstacle_bench.py"; /usr/bin/python3 bench/obstacle_bench.py $(BUILD)/apps/fricon/fricon
	@echo "== bench/quadratic_bench.py"; /usr/bin/python3 bench/quadratic_bench.py $(BUILD)/apps/fricon/fricon
	@echo "== bench/tfeti_bench.py"; /usr/bin/python3 bench/tfeti_bench.py $(BUILD)/apps/fricon/fricon \
	  --scalability 8 16 --preconditioners --series 16 --search \
	  $$($(BUILD)/apps/fricon/fricon --version | grep -q petsc && echo --weak 16 20)
	@if [ -n "$(BENCH_LARGE)" ]; then echo "== bench/tfeti_bench.py (large)"; \
	  /usr/bin/python3 bench/tfeti_bench.py $(BUILD)/apps/fricon/fricon --scalability 8 16 24 32 \
	  --preconditioners --scaling --sizes 24 500 1000 3000 --series 24 32 48 --series-tfeti-only 64; \
	  if $(BUILD)/apps/fricon/fricon --version | grep -q petsc; then \
	  /usr/bin/python3 bench/tfeti_bench.py $(BUILD)/apps/fricon/fricon --scalability --series \
	  --weak 24 30; fi; fi

format:
	clang-format -i $$(git ls-files '*.cpp' '*.hpp')

clean:
	rm -rf $(BUILD) $(SAN_BUILD) build-fuzz

# make fuzz    fuzz the readers (problem file, Siconos .dat, dual) with libFuzzer (clang, ASan +
#              UBSan) for FUZZ_SECONDS each, in their own build (build-fuzz). See docs/fuzzing.md.
# make test-fuzz, part of make test: the same build, each target FUZZ_SMOKE_SECONDS from its seeds
#              only (a fresh corpus), so that the fuzz build and targets cannot break unseen.
FUZZ_SECONDS ?= 60
FUZZ_SMOKE_SECONDS ?= 5
.PHONY: fuzz
fuzz: deps
	bash fuzz/run.sh $(FUZZ_SECONDS)

test-fuzz: deps
	FUZZ_FRESH_CORPUS=1 UNITY=$(UNITY) bash fuzz/run.sh $(FUZZ_SMOKE_SECONDS)
