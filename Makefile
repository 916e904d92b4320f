# The two commands of the README's quick start, plus their parts.
#   make demo   install what is missing, build, render the Cornell box, print the image's path
#   make test   install what is missing, build, run the whole test suite
BUILD_DIR ?= build
JOBS ?= $(shell nproc)

.PHONY: all deps build demo test bench clean sanitize-build sanitize fuzz fuzz-heap

all: build

deps:
	@tools/install-deps.sh

build: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release --log-level=WARNING
	@cmake --build $(BUILD_DIR) -j $(JOBS)

demo: build
	@mkdir -p out
	@$(BUILD_DIR)/bin/wavetrace render scenes/cornell.json --spp 32 -o out/cornell.png

# Tests that measure something (e.g. agreement with Embree) leave a line in build/reports/.
# check-deps first: every package the build used must come from tools/install-deps.sh.
test: build
	@tools/check-deps.sh $(BUILD_DIR)
	@rm -rf $(BUILD_DIR)/reports
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)
	@cat $(BUILD_DIR)/reports/*.txt 2>/dev/null || true

# The sanitized build (clang, ASan + UBSan incl. float-cast-overflow, libFuzzer) in its own
# folder, with only what its checks need. `make sanitize` (CI runs it after `make test`): the
# loader, CLI, BVH and engine tests under the sanitizers, then each fuzz target for a fixed
# number of executions. `make fuzz FUZZ_SECONDS=600`: explore longer and grow the corpus.
SAN_DIR ?= build-sanitize
FUZZ_HEAP_DIR ?= build-fuzz-heap
# clang with the system's binutils, for the sanitized and the fuzz-heap builds
# (line tables only: all a sanitizer's stack trace needs, and a quicker build than full -g).
# Highway's lane code is compiled for one target of each width, EMU128 (4 lanes), AVX2 (8)
# and AVX3 (16), not for SSSE3 and SSE4 beside them (4 lanes too; HWY_DISABLED_TARGETS 6144 =
# HWY_SSSE3 | HWY_SSE4 in Highway 1.0): the release build tests every target, and this cuts
# the time of the sanitized build's lane kernels by two fifths.
CLANG_CMAKE = -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  '-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -gline-tables-only -DNDEBUG' \
  -DCMAKE_CXX_FLAGS=-DHWY_DISABLED_TARGETS=6144 \
  -DCMAKE_AR=/usr/bin/ar -DCMAKE_RANLIB=/usr/bin/ranlib -DCMAKE_LINKER=/usr/bin/ld \
  -DWAVETRACE_FUZZ=ON -DWAVETRACE_BUILD_PYTHON=OFF --log-level=WARNING
# Peak-memory bounds mean nothing under ASan (its shadow memory and quarantine), so that test
# runs only in `make test`; so do the strategies' statistical tests, the engines' agreement
# on Mitsuba's scenes and compare's test against 1,024-spp renders, whose renders under ASan
# would take a shard most of its time (their code paths run in the Wavefront, Megakernel and
# other Compare tests here too). The suites named
# here must live in tests/CMakeLists.txt's WAVETRACE_SANITIZED_TEST_SOURCES.
SAN_TESTS ?= Check*:SceneLoader.*:MitsubaScenes.*:PbrtScenes.*:Cli.*:Hostile*:Bvh.*:Triangle.*:Sphere.*:Quad.*:MeshFiles.*:MeshAttributes.*:Wavefront.*:Megakernel.*:Kernels.*:Lanes.*:Films.*:CompareImages.*:-Cli.WavefrontMemoryDoesNotGrowWithSamples:Megakernel.StrategiesAgree:Megakernel.MisEarnsItsName:Wavefront.EqualsTheMegakernelOnMitsubasScenes:PbrtScenes.BitterlisCornellBoxRendersTungstensImageMean:Cli.CompareTellsNoiseFromADifferentImage
# Sized so that the seven targets, side by side on CI's two cores, end together in about 2
# minutes on a slow machine (a Zen 1; the millions each target has had are in
# docs/fuzzing.md). An XML execution loads a dozen shapes, meshes and images, a mesh execution
# goes through Assimp, and an image execution decodes up to 2^14 texels per byte of file:
# fewer runs keep them level with the others.
FUZZ_RUNS ?= 6000
FUZZ_XML_RUNS ?= 2500
FUZZ_MESH_RUNS ?= 3500
FUZZ_IMAGE_RUNS ?= 2000
FUZZ_SECONDS ?= 600

sanitize-build: deps
	@cmake -S . -B $(SAN_DIR) $(CLANG_CMAKE) -DWAVETRACE_SANITIZE=ON
	@cmake --build $(SAN_DIR) -j $(JOBS) --target wavetrace_cli wavetrace_tests fuzz_scene fuzz_xml fuzz_pbrt fuzz_mesh fuzz_film fuzz_image fuzz_volume

sanitize: sanitize-build
	@tools/check-deps.sh $(SAN_DIR)
	@tools/run-sanitized-tests.sh $(SAN_DIR) $(JOBS) '$(SAN_TESTS)'
	@FUZZ_XML_RUNS=$(FUZZ_XML_RUNS) FUZZ_MESH_RUNS=$(FUZZ_MESH_RUNS) FUZZ_IMAGE_RUNS=$(FUZZ_IMAGE_RUNS) \
	  tools/run-fuzzers.sh $(SAN_DIR) --runs $(FUZZ_RUNS)

fuzz: sanitize-build
	@tools/run-fuzzers.sh $(SAN_DIR) --seconds $(FUZZ_SECONDS)

# Heap damage inside Assimp, which ASan sees only late (Assimp is not instrumented): fuzz_mesh
# built without ASan, under glibc's heap checks, FUZZ_RUNS executions from each seed in SEEDS.
SEEDS ?= 2 3 4 5 6 7 8 9
fuzz-heap: deps
	@cmake -S . -B $(FUZZ_HEAP_DIR) $(CLANG_CMAKE)
	@cmake --build $(FUZZ_HEAP_DIR) -j $(JOBS) --target fuzz_mesh >/dev/null
	@tools/fuzz-heap.sh $(FUZZ_HEAP_DIR) $(FUZZ_RUNS) $(SEEDS)

# The benchmark suite: both engines side by side, our BVH vs Embree, thread scaling,
# convergence, kernel micro-benchmarks; results/ gets JSON, CSV and SVG plots.
bench: build
	@tools/install-deps.sh --bench
	@$(BUILD_DIR)/bin/wavetrace_bench --out results
	@$(BUILD_DIR)/bin/kernel_bench --benchmark_out=results/kernels.json --benchmark_out_format=json
	@gnuplot -e "dir='results'" bench/plot.gp
	@echo "results in results/ (JSON, CSV, SVG)"

clean:
	rm -rf $(BUILD_DIR) $(SAN_DIR) out
