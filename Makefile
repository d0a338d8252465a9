# ragdoll_sim: make deps | build | run | test | clean   (see README.md)
SHELL := /bin/bash
export PATH := /usr/bin:$(PATH)
.NOTPARALLEL:
.PHONY: deps build run test bench bench_compare fuzz clean

# clang, its libFuzzer / sanitizer runtimes and OpenMP: the ASan + UBSan build of the ROS-free
# gtests and the fuzz targets (`make test` runs the fuzz targets briefly, `make fuzz` for
# FUZZ_SECONDS each).
FUZZ_DEBS := clang-14 libclang-rt-14-dev libomp-14-dev

# The Python module (pybind11), ragdoll_batch and its Dask fan-out, plots and their tests;
# iproute2 for the test that runs workers in network namespaces.
PY_DEBS := pybind11-dev python3-dev python3-numpy python3-yaml python3-pandas python3-matplotlib \
           python3-tqdm python3-distributed python3-pytest python3-rospy iproute2

# Debian packages the package needs to build, run and test (ROS 1 from Debian, no /opt/ros),
# plus the Python message modules that rostopic / rosservice need for the README's examples.
DEBS := build-essential cmake googletest libgtest-dev \
        ros-base-dev libroscpp-dev libtf2-ros-dev libvisualization-msgs-dev libgeometry-msgs-dev \
        libsensor-msgs-dev libstd-srvs-dev ros-message-generation liburdfdom-dev \
        libinteractive-markers-dev \
        libconsole-bridge-dev libeigen3-dev catkin python3-rostest librostest-dev ros-core \
        python3-rostopic rviz xvfb imagemagick \
        python3-geometry-msgs python3-std-srvs python3-sensor-msgs python3-tf2-msgs \
        python3-visualization-msgs \
        libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure \
        libros-rosgraph-msgs-dev python3-rosgraph-msgs librosbag-dev python3-rosbag \
        ros-robot-state-publisher libassimp-dev libtinyxml2-dev libsdformat-dev libyaml-cpp-dev rosbash \
        $(PY_DEBS) $(FUZZ_DEBS)


deps:
	@scripts/deps.sh $(DEBS)

build:
	@scripts/build.sh

# WORLD=stairs (a shipped world by name) or WORLD=path/to/file.world
run: deps build
	@WORLD="$(WORLD)" scripts/run.sh

test: deps build
	@scripts/test.sh

# Debian packages only the benchmark needs (the peer engines and the plot); `make test` never
# installs or builds any of it.
BENCH_DEBS := libmujoco-dev libbullet-dev libode-dev libtinyxml2-dev liburdfdom-dev python3-matplotlib \
              valgrind

# Release build of bench/bench_ragdoll and of the peer benches (../shared/peers or PEERS_DIR),
# ROUNDS (default 3) alternating rounds of scenes a, b, c, the scaling scene g and our p, s
# (ours twice: the default float lanes, lanes=0, and the double rows, lanes=1);
# writes bench/results_raw.txt, bench/RESULTS.md and bench/scaling.png (scripts/bench.sh).
bench: deps
	@scripts/deps.sh $(BENCH_DEBS)
	@scripts/bench.sh

# Two bench_ragdoll binaries interleaved, old and new back to back in each of ROUNDS (default 5)
# rounds, scenes b, c, p and one awake ragdoll, sleeping off: a Markdown table of the steps/s and
# new / old (scripts/bench_compare.sh; OLD_OPTS, NEW_OPTS, THREADS, STEPS, OUT_MD there).
bench_compare:
	@scripts/bench_compare.sh "$(OLD)" "$(NEW)" $(ROUNDS)

# libFuzzer targets (test/fuzz) built with clang + ASan + UBSan, FUZZ_SECONDS (default 60) each;
# prints the executions and any crash, exits non-zero on a crash (scripts/fuzz.sh).
FUZZ_SECONDS ?= 60
fuzz: deps
	@scripts/deps.sh $(FUZZ_DEBS)
	@FUZZ_SECONDS=$(FUZZ_SECONDS) scripts/fuzz.sh

clean:
	rm -rf .ws
