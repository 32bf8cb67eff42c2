# meshfix.h: `make demo` shows a repair, `make test` runs every test, `make bench` measures.
CC ?= cc
CXX ?= c++
CFLAGS ?= -O2 -g
WARN = -Wall -Wextra -Wpedantic -Wshadow
SANITIZE = -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
OPENMESH = -lOpenMeshCore
B = build
HEADERS = meshfix.h examples/meshio.h examples/meshgen.h examples/sdfmesh.h

all: $(B)/meshfix $(B)/sdf_demo

$(B):
	mkdir -p $(B)

# the command-line tool (tools/meshfix): C++17, glTF through Debian's
# libtinygltf-dev (-ltinygltf); the library and the examples' loaders as C99
TOOL_SOURCES = $(wildcard tools/meshfix/*.cpp)
TOOL_HEADERS = $(wildcard tools/meshfix/*.h)
# --mark FILE.png through libpng (Debian's libpng-dev) when pkg-config knows
# it or its header is installed; `make PNG=` builds without it (MESHFIX_TOOL_NO_PNG)
PNG_PKG := $(shell pkg-config --exists libpng 2>/dev/null && echo yes)
PNG_FOUND = $(if $(PNG_PKG)$(wildcard /usr/include/png.h),yes,)
PNG ?= $(PNG_FOUND)
TOOL_PNG_FLAGS = $(if $(PNG),$(if $(PNG_PKG),$(shell pkg-config --cflags libpng),),-DMESHFIX_TOOL_NO_PNG)
TOOL_PNG_LIBS = $(if $(PNG),$(if $(PNG_PKG),$(shell pkg-config --libs libpng),-lpng),)

$(B)/meshfix: $(TOOL_SOURCES) $(TOOL_HEADERS) tools/meshfix/libs.c $(HEADERS) | $(B)
	@$(if $(PNG),:,echo "meshfix: building without PNG support (--mark FILE.png):" \
	    $(if $(PNG_FOUND),"PNG= given","no libpng (pkg-config libpng, /usr/include/png.h; Debian: apt-get install libpng-dev)"))
	$(CC) -std=c99 $(CFLAGS) $(WARN) -c -o $(B)/meshfix_libs.o tools/meshfix/libs.c
	$(CXX) -std=c++17 $(CFLAGS) $(WARN) $(TOOL_PNG_FLAGS) -o $@ $(TOOL_SOURCES) $(B)/meshfix_libs.o -ltinygltf \
	    $(TOOL_PNG_LIBS) -pthread

$(B)/demo_mesh: examples/demo_mesh.c $(HEADERS) | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -o $@ examples/demo_mesh.c -lm

$(B)/sdf_demo: examples/sdf_demo.c $(HEADERS) | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -o $@ examples/sdf_demo.c -lm

# Each C suite is built four ways: plain, with the sanitizers, with
# -O3 -ffast-math (what engines build with) and, where a 32-bit toolchain
# is installed (tests/run_all.sh checks), with -m32.
SUITES = test_meshfix test_sdf test_visibility test_hostile test_trust test_api
FAST = -O3 -ffast-math -g

$(B)/test_%: tests/test_%.c tests/check.h tests/internals.h tests/scenes.h tests/models.h $(HEADERS) | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -pthread -o $@ $< -lm

$(B)/test_%_asan: tests/test_%.c tests/check.h tests/internals.h tests/scenes.h tests/models.h $(HEADERS) | $(B)
	$(CC) -std=c99 -O1 -g $(WARN) $(SANITIZE) -pthread -o $@ $< -lm

$(B)/test_%_fast: tests/test_%.c tests/check.h tests/internals.h tests/scenes.h tests/models.h $(HEADERS) | $(B)
	$(CC) -std=c99 $(FAST) $(WARN) -pthread -o $@ $< -lm

$(B)/test_%_m32: tests/test_%.c tests/check.h tests/internals.h tests/scenes.h tests/models.h $(HEADERS) | $(B)
	$(CC) -m32 -std=c99 $(CFLAGS) $(WARN) -pthread -o $@ $< -lm

$(B)/test_openmesh: tests/test_openmesh.cpp $(HEADERS) | $(B)
	$(CXX) -std=c++17 $(CFLAGS) $(WARN) -o $@ tests/test_openmesh.cpp $(OPENMESH)

# The bench (tests/bench.cpp, tests/bench/*): Embree 3 is a bench-only
# dependency, used when its header is installed (Debian libembree-dev);
# `make bench EMBREE=` builds without it. BENCH_ARGS=--quick for a short run.
# -Wno-maybe-uninitialized: false positives at -O2 inside OpenMesh's headers and
# where tests/internals.h's bind_mesh inlines meshfix__bind.
EMBREE ?= $(if $(wildcard /usr/include/embree3/rtcore.h),yes,)
BENCH_EMBREE = $(if $(EMBREE),-DMESHFIX_BENCH_EMBREE,)
BENCH_EMBREE_LIB = $(if $(EMBREE),-lembree3,)
BENCH_SOURCES = tests/bench.cpp tests/bench/rays.cpp tests/bench/cut.cpp tests/bench/quality.cpp \
                tests/bench/adversarial.cpp
BENCH_ARGS ?=

$(B)/bench: $(BENCH_SOURCES) tests/bench/common.h tests/internals.h $(HEADERS) | $(B)
	$(CXX) -std=c++17 -O2 -DNDEBUG $(WARN) -Wno-maybe-uninitialized $(BENCH_EMBREE) -o $@ $(BENCH_SOURCES) \
	    $(OPENMESH) $(BENCH_EMBREE_LIB) -pthread

# the quality programs the bench runs (part 3)
$(B)/stl_truth: tests/eval/stl_truth.c meshfix.h | $(B)
	$(CC) -std=c99 -O2 -I. -o $@ tests/eval/stl_truth.c -lm

$(B)/scenes_eval: tests/eval/scenes_eval.c tests/scenes.h $(HEADERS) | $(B)
	$(CC) -std=c99 -O2 -I. -o $@ tests/eval/scenes_eval.c -lm

demo: $(B)/meshfix $(B)/demo_mesh
	@$(B)/demo_mesh $(B)/demo_input.obj
	@echo
	@echo "--- the plain flood fill (policy seed) follows its first triangle, one of the reversed 70%:"
	@$(B)/meshfix --policy seed $(B)/demo_input.obj $(B)/demo_seed.obj | sed -n '/^repair/,$$p'
	@echo
	@echo "--- meshfix's default (policy auto): each closed shell faces out:"
	@$(B)/meshfix $(B)/demo_input.obj $(B)/demo_fixed.obj --mark $(B)/demo_marked.ply
	@# the README shows docs/demo_marked.png, this picture (tests/test_cli.sh compares them)
	@$(if $(PNG),$(B)/meshfix --quiet $(B)/demo_input.obj $(B)/demo_fixed.obj --mark $(B)/demo_marked.png,:)
	@echo
	@echo "wrote $(B)/demo_fixed.obj and $(B)/demo_marked.ply (flipped faces red; open it in MeshLab or Blender)"
	@$(if $(PNG),echo "and $(B)/demo_marked.png (the same marks drawn: front, back, top and oblique views)",:)

test: $(B)/meshfix $(B)/demo_mesh $(B)/sdf_demo $(SUITES:%=$(B)/%) $(SUITES:%=$(B)/%_asan) $(SUITES:%=$(B)/%_fast) \
      $(B)/test_openmesh
	@CC="$(CC)" CXX="$(CXX)" MAKE="$(MAKE)" bash tests/run_all.sh

bench: $(B)/bench $(B)/stl_truth $(B)/scenes_eval
	$(B)/bench --build $(B) $(BENCH_ARGS)

clean:
	rm -rf $(B)

# libFuzzer targets for the library and the loaders; FUZZ_SECONDS each (default 60)
fuzz:
	bash tests/fuzz/run.sh

sdf-demo: $(B)/sdf_demo
	$(B)/sdf_demo $(B)/sdf_demo.obj

.PHONY: all demo sdf-demo test bench fuzz clean
