# The two commands of the README. Both install what is missing (scripts/setup.sh) first.
BUILD ?= build
JOBS ?= $(shell nproc)
SCENE ?= atrium
OUT ?= out/$(SCENE)

.PHONY: run test test-sanitized setup build bench asan asan-configure format clean

run: build
	./$(BUILD)/photovr render --scene $(SCENE) --denoise full --out $(OUT)

# The release suite, then the sanitizer suite (test-sanitized): CI runs both.
test: build
	cd $(BUILD) && ctest --output-on-failure -j$(JOBS)
	@./scripts/skipped_tests.sh $(BUILD)
	$(MAKE) --no-print-directory test-sanitized

setup:
	./scripts/setup.sh

build: setup
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	cmake --build $(BUILD) -j$(JOBS)

# The separate benchmarks, each writing a CSV to out/bench/: tracer vs raw Embree
# (bench_trace), hybrid stage times (bench_hybrid), denoiser passes and equal-time quality
# (bench_denoise), what each skip saves (bench_skips), compositor vs G-buffer and lens
# sampling (bench_compositor), overscan margins (bench_overscan), the Sobol sampler against
# the random one (bench_sampler), stereo path reuse on against off (bench_stereo), an
# animated frame against a static one (bench_animation), the whole-image passes outside the
# tracer, serial against now (bench_passes).
# `photovr bench [--quick]`
# is the error-vs-time harness. Not
# tests: their numbers depend on the machine and its load.
bench: build
	./$(BUILD)/bench/photovr_bench_trace --out out/bench
	./$(BUILD)/bench/photovr_bench_hybrid --out out/bench
	./$(BUILD)/bench/photovr_bench_denoise --out out/bench
	./$(BUILD)/bench/photovr_bench_skips --out out/bench
	./$(BUILD)/bench/photovr_bench_compositor --out out/bench
	./$(BUILD)/bench/photovr_bench_overscan --out out/bench
	./$(BUILD)/bench/photovr_bench_sampler --out out/bench
	./$(BUILD)/bench/photovr_bench_stereo --out out/bench
	./$(BUILD)/bench/photovr_bench_animation --out out/bench
	./$(BUILD)/bench/photovr_bench_passes --out out/bench

# AddressSanitizer + UndefinedBehaviorSanitizer build. `make asan` runs the whole suite under
# it (24 min of tests on 2 cores); `make test` runs the modules in SANITIZED_MODULES, the part
# that fits CI's time beside the release suite: every input reader and its fuzz tests
# (core: glTF, images, environment maps; hmd: HID reports, recordings, pose scripts) and the
# whole CPU tracer (trace). Their GL-bound neighbours (gl, hybrid, app) spend most of their
# time inside llvmpipe, which is not instrumented.
SANITIZED_MODULES ?= photovr_core_tests photovr_trace_tests photovr_hmd_tests
# detect_leaks=0: Mesa's llvmpipe and the GL loaders keep process-lifetime allocations that
# LeakSanitizer reports as leaks; use-after-free, overflows and UB are all checked.
# halt_on_error (ASan's default) and -fno-sanitize-recover=undefined make any report a failure.
empty :=
space := $(empty) $(empty)
SANITIZER_ENV = ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1

asan-configure: setup
	cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPHOTOVR_SANITIZE=ON >/dev/null

asan: asan-configure
	cmake --build build-asan -j$(JOBS)
	cd build-asan && $(SANITIZER_ENV) ctest --output-on-failure -j$(JOBS)
	@./scripts/skipped_tests.sh build-asan

test-sanitized: asan-configure
	cmake --build build-asan -j$(JOBS) --target $(SANITIZED_MODULES)
	cd build-asan && $(SANITIZER_ENV) ctest --output-on-failure --no-tests=error -j$(JOBS) \
	  -L '^($(subst $(space),|,$(strip $(SANITIZED_MODULES))))$$'
	@./scripts/skipped_tests.sh build-asan

format:
	git ls-files '*.cpp' '*.h' | xargs clang-format -i

clean:
	rm -rf $(BUILD) build-asan
