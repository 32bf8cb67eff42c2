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

$(B)/meshfix: examples/meshfix.c $(HEADERS) | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -o $@ examples/meshfix.c -lm

$(B)/demo_mesh: examples/demo_mesh.c $(HEADERS) | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -o $@ examples/demo_mesh.c -lm

$(B)/test_meshfix: tests/test_meshfix.c $(HEADERS) | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -o $@ tests/test_meshfix.c -lm

$(B)/test_meshfix_asan: tests/test_meshfix.c $(HEADERS) | $(B)
	$(CC) -std=c99 -O1 -g $(WARN) $(SANITIZE) -o $@ tests/test_meshfix.c -lm

$(B)/sdf_demo: examples/sdf_demo.c $(HEADERS) | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -o $@ examples/sdf_demo.c -lm

$(B)/test_sdf: tests/test_sdf.c $(HEADERS) | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -o $@ tests/test_sdf.c -lm

$(B)/test_sdf_asan: tests/test_sdf.c $(HEADERS) | $(B)
	$(CC) -std=c99 -O1 -g $(WARN) $(SANITIZE) -o $@ tests/test_sdf.c -lm

$(B)/test_visibility: tests/test_visibility.c $(HEADERS) | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -o $@ tests/test_visibility.c -lm

$(B)/test_visibility_asan: tests/test_visibility.c $(HEADERS) | $(B)
	$(CC) -std=c99 -O1 -g $(WARN) $(SANITIZE) -o $@ tests/test_visibility.c -lm

$(B)/test_hostile: tests/test_hostile.c $(HEADERS) | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -o $@ tests/test_hostile.c -lm

$(B)/test_hostile_asan: tests/test_hostile.c $(HEADERS) | $(B)
	$(CC) -std=c99 -O1 -g $(WARN) $(SANITIZE) -o $@ tests/test_hostile.c -lm

$(B)/test_openmesh: tests/test_openmesh.cpp $(HEADERS) | $(B)
	$(CXX) -std=c++17 $(CFLAGS) $(WARN) -o $@ tests/test_openmesh.cpp $(OPENMESH)

$(B)/bench: tests/bench.cpp $(HEADERS) | $(B)
	$(CXX) -std=c++17 -O2 -DNDEBUG $(WARN) -o $@ tests/bench.cpp $(OPENMESH)

demo: $(B)/meshfix $(B)/demo_mesh
	@$(B)/demo_mesh $(B)/demo_input.obj
	@echo
	@echo "--- the plain flood fill (policy seed) follows its first triangle, one of the reversed 70%:"
	@$(B)/meshfix --policy seed $(B)/demo_input.obj $(B)/demo_seed.obj | sed -n '/^repair/,$$p'
	@echo
	@echo "--- meshfix's default (policy auto): each closed shell faces out:"
	@$(B)/meshfix $(B)/demo_input.obj $(B)/demo_fixed.obj --mark $(B)/demo_marked.ply
	@echo
	@echo "wrote $(B)/demo_fixed.obj and $(B)/demo_marked.ply (flipped faces red; open it in MeshLab or Blender)"

test: $(B)/meshfix $(B)/demo_mesh $(B)/sdf_demo $(B)/test_meshfix $(B)/test_meshfix_asan $(B)/test_sdf $(B)/test_sdf_asan \
      $(B)/test_visibility $(B)/test_visibility_asan $(B)/test_hostile $(B)/test_hostile_asan $(B)/test_openmesh
	@CC="$(CC)" CXX="$(CXX)" bash tests/run_all.sh

bench: $(B)/bench
	$(B)/bench

clean:
	rm -rf $(B)

# libFuzzer targets for the library and the loaders; FUZZ_SECONDS each (default 60)
fuzz:
	bash tests/fuzz/run.sh

sdf-demo: $(B)/sdf_demo
	$(B)/sdf_demo $(B)/sdf_demo.obj

.PHONY: all demo sdf-demo test bench fuzz clean
