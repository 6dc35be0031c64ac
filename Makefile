# virtcom top-level entry points. Every target that builds first installs the
# Debian packages it needs (`make deps`), so each works on a fresh machine.
JOBS       ?= $(shell nproc)
BUILD      ?= build/release
TESTBUILD  ?= build/asan
FUZZBUILD  ?= build/fuzz
FUZZ_SECONDS ?= 600
CMAKE_GEN  := -G Ninja
# ccache (Debian) keeps rebuilds cheap, also across clones: paths are hashed relative to the checkout.
export CCACHE_BASEDIR := $(CURDIR)
export CCACHE_NOHASHDIR := 1
LAUNCHER   := -DCMAKE_CXX_COMPILER_LAUNCHER=ccache

APT_PACKAGES := build-essential cmake ninja-build g++ clang-19 libclang-rt-19-dev \
                libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev \
                libyaml-dev nlohmann-json3-dev libpugixml-dev libcpp-httplib-dev chromium libmodbus-dev mbpoll pkg-config nodejs ccache \
                libsqlite3-dev libgraphviz-dev lcov libxml2-utils libssl-dev \
                libopenmpi-dev openmpi-bin

.PHONY: all deps build test demo bench fuzz fuzz-build clean

all: build

deps:
	@missing=""; for p in $(APT_PACKAGES); do \
	  dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q 'install ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  echo "make deps: installing$$missing"; \
	  SUDO=""; [ "$$(id -u)" -ne 0 ] && SUDO=sudo; \
	  $$SUDO apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq --no-install-recommends $$missing >/dev/null; \
	fi

build: deps
	@cmake -S . -B $(BUILD) $(CMAKE_GEN) $(LAUNCHER) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

fuzz-build: deps
	@cmake -S . -B $(FUZZBUILD) $(CMAKE_GEN) $(LAUNCHER) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_CXX_COMPILER=clang++-19 -DCMAKE_C_COMPILER=clang-19 -DVIRTCOM_FUZZ_ONLY=ON >/dev/null
	@cmake --build $(FUZZBUILD) -j $(JOBS)

test: deps fuzz-build
	@cmake -S . -B $(TESTBUILD) $(CMAKE_GEN) $(LAUNCHER) -DCMAKE_BUILD_TYPE=Debug -DVIRTCOM_SANITIZE=ON >/dev/null
	@cmake --build $(TESTBUILD) -j $(JOBS)
	@# The npm ads-client and node-opcua-client for the ADS and OPC UA e2e tests and playwright-core for the HMI's browser tests
	@# (Debian's nodejs may come without npm).
	@command -v npm >/dev/null 2>&1 || { SUDO=""; [ "$$(id -u)" -ne 0 ] && SUDO=sudo; \
	  DEBIAN_FRONTEND=noninteractive $$SUDO apt-get install -y -qq --no-install-recommends npm >/dev/null; }
	@npm ci --prefix tests/e2e/ads --no-audit --no-fund --loglevel=error >/dev/null
	@npm ci --prefix tests/e2e/opcua --no-audit --no-fund --loglevel=error >/dev/null
	@npm ci --prefix tests/e2e/hmi --no-audit --no-fund --loglevel=error >/dev/null
	@cd $(TESTBUILD) && FUZZ_BUILD_DIR=$(abspath $(FUZZBUILD)) VIRTCOM_REQUIRE_BROWSER=1 VIRTCOM_REQUIRE_MBPOLL=1 \
	  ctest --output-on-failure -j $(JOBS)

demo: build
	@mkdir -p build/demo
	@echo "== gearbox cell, initial sequence (seed Figure 11a)"
	@$(BUILD)/src/cli/virtcom run examples/gearbox-cell/cell.yaml --set MAIN.sequence=1 \
	  --report build/demo/gearbox-sequence1.html
	@echo; echo "== gearbox cell, refined sequence (seed Figure 11c)"
	@$(BUILD)/src/cli/virtcom run examples/gearbox-cell/cell.yaml --set MAIN.sequence=3 \
	  --report build/demo/gearbox-sequence3.html --json build/demo/gearbox-sequence3.json \
	  --vcd build/demo/gearbox-sequence3.vcd --signal Robot1.busy --signal Robot2.busy --signal Press.actualForce
	@echo; echo "Reports: build/demo/gearbox-sequence1.html build/demo/gearbox-sequence3.html"

bench: build
	@$(BUILD)/bench/virtcom_bench --benchmark_counters_tabular=true
	@$(BUILD)/bench/virtcom_modbus_bench
	@$(BUILD)/bench/virtcom_optimise_bench

# Every fuzz target (or those of FUZZ_TARGETS) for FUZZ_SECONDS (default 600) each on the
# checked-in corpus (grown corpora kept in build/fuzz-campaign); prints executions, coverage and
# findings (docs/security.md).
fuzz: fuzz-build
	@FUZZ_BUILD_DIR=$(abspath $(FUZZBUILD)) FUZZ_TARGETS="$(FUZZ_TARGETS)" bash tests/fuzz/run_fuzz_campaign.sh $(FUZZ_SECONDS) build/fuzz-campaign

clean:
	rm -rf build
