# The two set-up commands of README.md: `make demo` and `make test`.
BUILD ?= build
JOBS ?= $(shell nproc)
.PHONY: setup build test demo bench clean format test-asan fuzz san-configure

setup:
	bash scripts/setup.sh

build: setup
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD) -j $(JOBS)

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) --timeout 600
	$(MAKE) test-asan
	$(MAKE) fuzz

# Sanitizers and fuzzing (docs/RELIABILITY.md): one clang build directory with
# ASan + UBSan and libFuzzer coverage serves the unit tests and the harnesses.
SAN_BUILD ?= build-san
FUZZ_SECONDS ?= 30
SAN_ENV = ASAN_OPTIONS=abort_on_error=1 LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp \
          UBSAN_OPTIONS=print_stacktrace=1

san-configure: setup
	CC=clang CXX=clang++ cmake -S . -B $(SAN_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DWB_FUZZ=ON

test-asan: san-configure
	cmake --build $(SAN_BUILD) -j $(JOBS) --target unit_tests
	cd $(SAN_BUILD) && $(SAN_ENV) ctest --output-on-failure -j $(JOBS) --timeout 600

fuzz: san-configure
	cmake --build $(SAN_BUILD) -j $(JOBS) --target fuzzers
	bash scripts/fuzz.sh $(SAN_BUILD) $(FUZZ_SECONDS) 2

demo: build
	bash scripts/demo.sh $(BUILD)/wavebake

bench: build
	bash bench/run_all.sh $(BUILD)

format:
	clang-format -i $$(git ls-files '*.h' '*.cc' '*.cpp')

clean:
	rm -rf $(BUILD)
