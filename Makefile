# The two commands of the README. Both install what is missing (scripts/setup.sh) first.
BUILD ?= build
JOBS ?= $(shell nproc)
SCENE ?= atrium
OUT ?= out/$(SCENE)

.PHONY: run test setup build bench asan format clean

run: build
	./$(BUILD)/photovr render --scene $(SCENE) --denoise full --out $(OUT)

test: build
	cd $(BUILD) && ctest --output-on-failure -j$(JOBS)

setup:
	./scripts/setup.sh

build: setup
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	cmake --build $(BUILD) -j$(JOBS)

# The separate benchmarks, each writing a CSV to out/bench/: tracer vs raw Embree
# (bench_trace), hybrid stage times (bench_hybrid), denoiser passes and equal-time quality
# (bench_denoise), what each skip saves (bench_skips), compositor vs G-buffer and lens
# sampling (bench_compositor), overscan margins (bench_overscan). `photovr bench [--quick]`
# is the error-vs-time harness. Not
# tests: their numbers depend on the machine and its load.
bench: build
	./$(BUILD)/bench/photovr_bench_trace --out out/bench
	./$(BUILD)/bench/photovr_bench_hybrid --out out/bench
	./$(BUILD)/bench/photovr_bench_denoise --out out/bench
	./$(BUILD)/bench/photovr_bench_skips --out out/bench
	./$(BUILD)/bench/photovr_bench_compositor --out out/bench
	./$(BUILD)/bench/photovr_bench_overscan --out out/bench

# AddressSanitizer + UndefinedBehaviorSanitizer build and the whole test suite under it.
asan: setup
	cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPHOTOVR_SANITIZE=ON >/dev/null
	cmake --build build-asan -j$(JOBS)
	# detect_leaks=0: Mesa's llvmpipe and the GL loaders keep process-lifetime allocations
	# that LeakSanitizer reports as leaks; use-after-free, overflows and UB are all checked.
	cd build-asan && ASAN_OPTIONS=detect_leaks=0 ctest --output-on-failure -j$(JOBS)

format:
	git ls-files '*.cpp' '*.h' | xargs clang-format -i

clean:
	rm -rf $(BUILD) build-asan
