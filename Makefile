# The two commands a newcomer needs: `make demo` and `make test`. `make eval` (not part of
# `make test`) measures image quality against ground truth and rewrites docs/quality.md.
BUILD_DIR ?= build
BUILD_TYPE ?= Release
JOBS ?= 2

.PHONY: all deps configure build test demo eval clean

all: build

deps:
	@bash deploy/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) >/dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

test: build
	@ctest --test-dir $(BUILD_DIR) --output-on-failure -j $(JOBS)

demo: build
	@bash deploy/demo.sh $(BUILD_DIR)

# The standard quality set: the table, the rules, the machine and a few side-by-side pictures
# (ground truth | reenactment | error) in docs/quality.md and docs/quality/.
# The subject is the skinned CesiumMan of the shared data (a realistic body, not cylinders).
SHARED_DATA ?= ../shared/data
EVAL_ARGS ?= --scenario turn-and-kick --body $(SHARED_DATA)/models/CesiumMan.glb \
             --methods thesis,steady,per-part,occlusion,blend,shape,profile,relit,fallback,surface,all --views 0,30,60,90,135,180 \
             --step 10 --image-pairs 90@90,165@180
eval: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS) --target reenact-eval
	@mkdir -p docs/quality
	@rm -f docs/quality/*.png
	@$(BUILD_DIR)/tests/eval/reenact-eval quality $(EVAL_ARGS) --images docs/quality \
		--json docs/quality/quality.json --markdown docs/quality.md

clean:
	rm -rf $(BUILD_DIR) demo-out var
