# ragdoll_sim: make deps | build | run | test | clean   (see README.md)
SHELL := /bin/bash
export PATH := /usr/bin:$(PATH)
.NOTPARALLEL:
.PHONY: deps build run test bench clean

# Debian packages the package needs to build, run and test (ROS 1 from Debian, no /opt/ros),
# plus the Python message modules that rostopic / rosservice need for the README's examples.
DEBS := build-essential cmake googletest libgtest-dev \
        ros-base-dev libroscpp-dev libtf2-ros-dev libvisualization-msgs-dev libgeometry-msgs-dev \
        libsensor-msgs-dev libstd-srvs-dev ros-message-generation liburdfdom-dev \
        libconsole-bridge-dev libeigen3-dev catkin python3-rostest librostest-dev ros-core \
        python3-rostopic rviz xvfb imagemagick \
        python3-geometry-msgs python3-std-srvs python3-sensor-msgs python3-tf2-msgs \
        python3-visualization-msgs

deps:
	@scripts/deps.sh $(DEBS)

build:
	@scripts/build.sh

run: deps build
	@scripts/run.sh

test: deps build
	@scripts/test.sh

# Release build of the core and bench/bench_ragdoll, run on the peer scenes a, b, c.
bench: deps
	@scripts/bench.sh

clean:
	rm -rf .ws
