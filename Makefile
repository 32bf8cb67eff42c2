# meshfix.h: `make demo` shows a repair (cc and c++ only), `make test` installs what the tests need
# (tests/install_deps.sh) and runs every test, `make bench` measures.
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

# The command-line tool (tools/meshfix): C++17, the library and the
# examples' loaders as C99; it needs nothing else. Each optional part is on
# when $(CXX), with this build's flags, finds its headers, and off
# otherwise; the build of the tool says once what is off and what to
# install. `make GLTF=` leaves glTF out even where it is installed. A part
# is a block of variables:
#   ifndef NAME / NAME := $(call have_headers,HEADER...) / endif
#   TOOL_FLAGS += ..., TOOL_LIBS += ...    what the tool is built with, on or off
#   TOOL_OFF += $(if $(NAME),,NAME)        and NAME_OFF, the line said when off
H := \#
have_headers = $(shell printf '$(H)if !__has_include(<%s>)\n$(H)error\n$(H)endif\n' $(1) | \
    $(CXX) $(CFLAGS) -E -x c++ - >/dev/null 2>&1 && echo yes)
TOOL_FLAGS :=
TOOL_LIBS :=
TOOL_OFF :=

# glTF (.gltf, .glb: tools/meshfix/gltf.cpp) through tinygltf and nlohmann json
ifndef GLTF
GLTF := $(call have_headers,tiny_gltf.h nlohmann/json.hpp)
endif
TOOL_FLAGS += $(if $(GLTF),,-DMESHFIX_TOOL_NO_GLTF)
TOOL_LIBS += $(if $(GLTF),-ltinygltf)
TOOL_OFF += $(if $(GLTF),,GLTF)
GLTF_OFF = glTF support: it refuses .gltf and .glb files (glTF needs tiny_gltf.h and nlohmann/json.hpp; \
    Debian: apt-get install libtinygltf-dev nlohmann-json3-dev)

TOOL_SOURCES = $(wildcard tools/meshfix/*.cpp)
TOOL_HEADERS = $(wildcard tools/meshfix/*.h)
# --mark FILE.png through libpng (tools/meshfix/render.cpp)
ifndef PNG
PNG := $(call have_headers,png.h)
endif
TOOL_FLAGS += $(if $(PNG),,-DMESHFIX_TOOL_NO_PNG)
TOOL_LIBS += $(if $(PNG),-lpng)
TOOL_OFF += $(if $(PNG),,PNG)
PNG_OFF = PNG support: --mark FILE.png is refused (it needs png.h; Debian: apt-get install libpng-dev)

$(B)/meshfix: $(TOOL_SOURCES) $(TOOL_HEADERS) tools/meshfix/libs.c $(HEADERS) $(B)/meshfix.options | $(B)
	@$(foreach o,$(TOOL_OFF),echo '$@ is built without $(subst ',,$($(o)_OFF))';) :
	$(CC) -std=c99 $(CFLAGS) $(WARN) -c -o $(B)/meshfix_libs.o tools/meshfix/libs.c
	$(CXX) -std=c++17 $(CFLAGS) $(WARN) $(TOOL_FLAGS) -o $@ $(TOOL_SOURCES) $(B)/meshfix_libs.o $(TOOL_LIBS) -pthread

# what the tool was built with: it is built again when that changes (a
# package installed or removed)
$(B)/meshfix.options: FORCE | $(B)
	@[ "$$(cat $@ 2>/dev/null)" = '$(strip $(TOOL_FLAGS) $(TOOL_LIBS))' ] || echo '$(strip $(TOOL_FLAGS) $(TOOL_LIBS))' >$@

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
$(B)/stl_truth: tests/eval/stl_truth.c tests/eval/calibration.h meshfix.h | $(B)
	$(CC) -std=c99 -O2 -I. -o $@ tests/eval/stl_truth.c -lm

# scores the tool's repair against the normals of real assets
# (tests/corpus/fetch_assets.sh): the tool's loaders and repair without main.cpp
ASSETS_EVAL_SOURCES = tests/eval/assets_eval.cpp $(filter-out tools/meshfix/main.cpp,$(TOOL_SOURCES))

$(B)/assets_eval: $(ASSETS_EVAL_SOURCES) $(TOOL_HEADERS) tools/meshfix/libs.c tests/eval/calibration.h $(HEADERS) | $(B)
	$(CC) -std=c99 $(CFLAGS) $(WARN) -I. -include tests/eval/calibration.h -DCALIBRATION_IMPLEMENTATION \
	    -c -o $(B)/assets_eval_libs.o tools/meshfix/libs.c
	$(CXX) -std=c++17 $(CFLAGS) $(WARN) $(TOOL_FLAGS) -Itools/meshfix -o $@ $(ASSETS_EVAL_SOURCES) $(B)/assets_eval_libs.o \
	    $(TOOL_LIBS) -pthread

$(B)/scenes_eval: tests/eval/scenes_eval.c tests/scenes.h $(HEADERS) | $(B)
	$(CC) -std=c99 -O2 -I. -o $@ tests/eval/scenes_eval.c -lm

demo: $(B)/meshfix $(B)/demo_mesh
	@$(B)/demo_mesh $(B)/demo_input.obj
	@echo
	@echo "--- the plain flood fill (policy seed) follows its first triangle, one of the reversed 70%:"
	@# its last line, the library's summary, counts the triangles it turned; the line
	@# printed says what that left: every closed shell consistent, and inside out
	@$(B)/meshfix --policy seed $(B)/demo_input.obj $(B)/demo_seed.obj >$(B)/demo_seed.txt
	@sed -n '/^repair/,$$p' $(B)/demo_seed.txt | sed '$$d'
	@echo "$$(sed '$$!d' $(B)/demo_seed.txt), and left $$(sed -n '/^repair/,$$s/^  patches .*(closed \([0-9]*\), inside-out \([0-9]*\)).*/\2 of its \1 closed shells/p' \
	    $(B)/demo_seed.txt) inside out: consistent now, and still wrong (a flood fill cannot tell out from in)"
	@echo
	@echo "--- meshfix's default (policy auto): each closed shell faces out:"
	@$(B)/meshfix $(B)/demo_input.obj $(B)/demo_fixed.obj --mark $(B)/demo_marked.ply
	@# the README shows docs/demo_marked.png, this picture (tests/test_cli.sh compares them)
	@$(if $(PNG),$(B)/meshfix --quiet $(B)/demo_input.obj $(B)/demo_fixed.obj --mark $(B)/demo_marked.png,:)
	@echo
	@echo "wrote $(B)/demo_fixed.obj and $(B)/demo_marked.ply (flipped faces red; open it in MeshLab or Blender)"
	@$(if $(PNG),echo "and $(B)/demo_marked.png (the same marks drawn: front, back, top and oblique views)",:)

# `make test` installs what the suites need first (tests/install_deps.sh:
# with apt-get as root; otherwise it names the apt-get line and stops),
# then builds with what is installed now; `make test-only` skips that step
# make test also fetches the corpus (tests/corpus/fetch.sh: real models from
# Debian packages, about 250 MB, downloaded once into build/corpus, nothing
# installed): the trust suite cuts OpenSCAD's projection.stl from it
test:
	@bash tests/install_deps.sh
	@[ -f $(B)/corpus/manifest.tsv ] || bash tests/corpus/fetch.sh $(B)/corpus >$(B)/corpus.log 2>&1 || \
	    echo "the corpus could not be fetched (see $(B)/corpus.log): its tests say SKIP"
	@$(MAKE) --no-print-directory test-only

test-only: $(B)/meshfix $(B)/demo_mesh $(B)/sdf_demo $(SUITES:%=$(B)/%) $(SUITES:%=$(B)/%_asan) \
      $(SUITES:%=$(B)/%_fast) $(B)/test_openmesh
	@CC="$(CC)" CXX="$(CXX)" MAKE="$(MAKE)" bash tests/run_all.sh

# `make check` (or `make quick`): the six C suites, plain builds, and the
# tool's own tests (tests/quick.sh); `make check WORD=cut` only the C tests
# whose names contain "cut", as `build/test_NAME WORD` does for one suite
check quick: $(B)/meshfix $(B)/demo_mesh $(SUITES:%=$(B)/%)
	@bash tests/quick.sh $(WORD)

$(B)/trust_eval: tests/eval/trust_eval.c tests/eval/calibration.h tests/scenes.h $(HEADERS) | $(B)
	$(CC) -std=c99 -O2 -I. -o $@ tests/eval/trust_eval.c -lm

$(B)/models_eval: tests/eval/models_eval.c tests/eval/calibration.h $(HEADERS) | $(B)
	$(CC) -std=c99 -O2 -I. -o $@ tests/eval/models_eval.c -lm

# AUTO's confidence: rows from the tune halves, fitted into meshfix.h's
# table (tests/eval/fit.sh; `make fit FIT_ARGS=--validate` leaves it alone)
$(B)/fit: tests/eval/fit.c | $(B)
	$(CC) -std=c99 -O2 $(WARN) -o $@ tests/eval/fit.c -lm

fit:
	bash tests/eval/fit.sh $(FIT_ARGS)

bench: $(B)/bench $(B)/stl_truth $(B)/scenes_eval $(B)/trust_eval $(B)/models_eval
	$(B)/bench --build $(B) $(BENCH_ARGS)

clean:
	rm -rf $(B)

# libFuzzer targets for the library and the loaders; FUZZ_SECONDS each (default 60)
fuzz:
	bash tests/fuzz/run.sh

sdf-demo: $(B)/sdf_demo
	$(B)/sdf_demo $(B)/sdf_demo.obj

# the Blender add-on (blender/): the add-on's Python with the meshfix module
# inside, its shared library built from the header by python/build.sh
BLENDER_ADDON = blender/__init__.py blender/repair.py blender/build.sh python/build.sh python/meshfix/__init__.py \
                python/meshfix/_native.c meshfix.h

# The browser page (js/page/): meshfix.h as WebAssembly and glTF-Transform's
# core vendored from js/node_modules, into build/page; needs node, npm, emcc.
page:
	@cd js && { [ -f node_modules/@gltf-transform/core/package.json ] || npm ci --no-audit --no-fund; } && \
		node scripts/build.mjs --if-stale && node scripts/page.mjs ../$(B)/page
	@echo "open it: python3 -m http.server -b 127.0.0.1 -d $(B)/page 8000, then http://127.0.0.1:8000/"

blender-addon: $(B)/meshfix_blender.zip

$(B)/meshfix_blender.zip: $(BLENDER_ADDON) | $(B)
	sh blender/build.sh $@

.PHONY: all demo sdf-demo blender-addon page test test-only check quick bench fit fuzz clean FORCE
FORCE:
