# virtcom top-level entry points. Every target that builds first installs the
# Debian packages it needs (`make deps`), so each works on a fresh machine.
JOBS       ?= $(shell nproc)
BUILD      ?= build/release
TESTBUILD  ?= build/asan
FUZZBUILD  ?= build/fuzz
CMAKE_GEN  := -G Ninja

APT_PACKAGES := build-essential cmake ninja-build g++ clang libclang-rt-14-dev \
                libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev \
                libyaml-cpp-dev nlohmann-json3-dev

.PHONY: all deps build test demo bench fuzz clean

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
	@cmake -S . -B $(BUILD) $(CMAKE_GEN) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

test: deps
	@cmake -S . -B $(TESTBUILD) $(CMAKE_GEN) -DCMAKE_BUILD_TYPE=Debug -DVIRTCOM_SANITIZE=ON >/dev/null
	@cmake --build $(TESTBUILD) -j $(JOBS)
	@cmake -S . -B $(FUZZBUILD) $(CMAKE_GEN) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang -DVIRTCOM_FUZZ_ONLY=ON >/dev/null
	@cmake --build $(FUZZBUILD) -j $(JOBS)
	@cd $(TESTBUILD) && FUZZ_BUILD_DIR=$(abspath $(FUZZBUILD)) ctest --output-on-failure -j $(JOBS)

demo: build
	@$(BUILD)/src/cli/virtcom exec examples/st/traffic_light.st --cycles 2000 --cycle-time 10ms --stats \
	  --print MAIN.phase --print MAIN.cycles --print MAIN.elapsed --print MAIN.walk

bench: build
	@$(BUILD)/bench/virtcom_bench --benchmark_counters_tabular=true

clean:
	rm -rf build
