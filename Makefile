# egosim: `make run` starts the simulator, `make test` runs every test.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
ARGS ?=
# `make test` runs the tests in this many pytest-xdist workers, a test file per worker at
# a time (module-scoped simulators and batch runs stay shared). Most tests wait on
# subprocesses, so more workers than cores pay.
TEST_WORKERS ?= 4
# Debian's ROS 1 (Noetic): test peers only, never a runtime dependency.
ROS_PEER_DEBS := python3-rospy python3-rosmaster python3-rostopic python3-rosservice \
	python3-rosparam python3-rosnode python3-rosbag python3-genpy ros-core-dev \
	python3-visualization-msgs \
	g++ pkg-config python3-opencv python3-sensor-msgs
# Debian's headless Chromium and its WebDriver: the live view's browser tests.
BROWSER_DEBS := chromium chromium-driver
# Cameras render with OpenGL on a headless EGL context (Mesa's llvmpipe on the CPU).
RENDER_DEBS := libegl1 libgl1 libegl-mesa0 libgl1-mesa-dri
SOURCES := $(wildcard src tests benchmarks examples)

.PHONY: run test lint ros-peers browser-peers render-libs benchmarks clean

$(BIN)/python:
	@$(PYTHON) -m venv $(VENV) 2>/dev/null || { \
		if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
			apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq python3-venv \
			&& $(PYTHON) -m venv $(VENV); \
		else \
			echo "error: '$(PYTHON) -m venv' failed: install python3-venv" >&2; exit 1; \
		fi; }
	$(BIN)/python -m pip install -q --upgrade pip

$(VENV)/.installed: $(BIN)/python pyproject.toml
	$(BIN)/pip install -q -e .
	@touch $@

$(VENV)/.installed-test: $(BIN)/python pyproject.toml
	$(BIN)/pip install -q -e ".[test]"
	@touch $@ $(VENV)/.installed

run: $(VENV)/.installed render-libs
	$(BIN)/egosim run $(ARGS)

render-libs:
	@if ldconfig -p 2>/dev/null | grep -q 'libEGL.so.1 ' && ldconfig -p | grep -q 'libGL.so.1 ' \
		&& ls /usr/lib/*/dri/swrast_dri.so >/dev/null 2>&1; then \
		echo "camera rendering libraries: present"; \
	elif [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
		echo "camera rendering libraries: installing $(RENDER_DEBS)"; \
		apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
			--no-install-recommends $(RENDER_DEBS); \
	else \
		echo "WARNING: EGL/Mesa libraries are missing and this is not root: cameras will be off."; \
		echo "         Install them: sudo apt-get install $(RENDER_DEBS)"; \
	fi

ros-peers:
	@if /usr/bin/python3 -c "import rospy, rosmaster, rostopic, rosservice, rosbag, genpy, cv2, sensor_msgs.msg, visualization_msgs" 2>/dev/null \
		&& [ -f /usr/include/ros/ros.h ]; then \
		echo "ROS 1 test peers: present"; \
	elif [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
		echo "ROS 1 test peers: installing $(ROS_PEER_DEBS)"; \
		apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
			--no-install-recommends $(ROS_PEER_DEBS); \
	else \
		echo "########################################################################"; \
		echo "# WARNING: Debian's ROS 1 test peers are missing and this is not root. #"; \
		echo "# Every test marked 'ros' or 'roscpp' (interop and end-to-end) will    #"; \
		echo "# SKIP. Install them: sudo apt-get install $(ROS_PEER_DEBS)"; \
		echo "########################################################################"; \
	fi

browser-peers:
	@if [ -x /usr/bin/chromium ] && [ -x /usr/bin/chromedriver ]; then \
		echo "browser test peers: present"; \
	elif [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
		echo "browser test peers: installing $(BROWSER_DEBS)"; \
		apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
			--no-install-recommends $(BROWSER_DEBS); \
	else \
		echo "WARNING: chromium and chromium-driver are missing and this is not root:"; \
		echo "the live view's browser tests will SKIP (sudo apt-get install $(BROWSER_DEBS))"; \
	fi

lint: $(VENV)/.installed-test
	$(BIN)/ruff check $(SOURCES)
	$(BIN)/ruff format --check $(SOURCES)
	$(BIN)/mypy

test: $(VENV)/.installed-test ros-peers browser-peers render-libs lint
	$(BIN)/pytest -n $(TEST_WORKERS) --dist loadfile

benchmarks: $(VENV)/.installed-test
	@for script in benchmarks/*.py; do echo "== $$script"; $(BIN)/python $$script || exit 1; done

clean:
	rm -rf $(VENV) .pytest_cache .ruff_cache build *.egg-info src/*.egg-info
