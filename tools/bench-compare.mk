# bench-compare.mk — `make bench-compare`: softrast against Mesa's llvmpipe on
# the benchmark scenes (docs/bench-compare.md). Included from the Makefile;
# it uses its CC, CFLAGS, ALL_CFLAGS, LIBS and its build/%.o rule.
# BENCH_COMPARE_ARGS passes options to build/bench-gl (see --help).

GL_PKGS        := egl opengl
GL_CFLAGS       = $(shell pkg-config --cflags $(GL_PKGS) 2>/dev/null)
GL_LIBS         = $(shell pkg-config --libs $(GL_PKGS) 2>/dev/null || echo -lEGL -lOpenGL)
BENCH_GL_OBJ   := $(patsubst %.c,build/%.o,$(wildcard tools/bench_gl*.c))
# The scenes come from the same studies library `softrast bench` runs.
BENCH_COMPARE_ARGS ?=

.PHONY: bench-compare deps-gl

# Offscreen EGL + desktop GL headers and libraries, and Mesa's EGL vendor and
# DRI drivers, which hold llvmpipe (swrast_dri.so).
GL_DEBS := pkg-config libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri

deps-gl:
	@sh tools/deps.sh $(GL_DEBS)

# The GL headers come with deps-gl; order-only, so they do not force a rebuild.
$(BENCH_GL_OBJ): ALL_CFLAGS += $(GL_CFLAGS)
$(BENCH_GL_OBJ): | deps-gl

build/bench-gl: $(BENCH_GL_OBJ) $(call APP_LIBS,build)
	@echo "  LINK    $@"
	@$(CC) $(CFLAGS) $^ $(LIBS) $(GL_LIBS) -o $@

# --truth draws the report's scenes, the scanned meshes among them.
bench-compare: deps deps-gl build/bench-gl $(if $(findstring --truth,$(BENCH_COMPARE_ARGS)),scans)
	./build/bench-gl $(BENCH_COMPARE_ARGS)

-include $(BENCH_GL_OBJ:.o=.d)

# ---- `make compare-open3d`: softrast's pinhole camera against Open3D's
# RaycastingScene (docs/open3d-compare.md), both held to an exact
# double-precision ray cast. Debian's python3-open3d is installed here only
# (never by `make test`). Its Embree skips rays whose mask is 0, which is
# every ray Open3D 0.16 casts: build/open3d_ray_mask.so, preloaded, sets the
# masks (tools/open3d_ray_mask.c). The table goes to build/open3d-compare.md.
# COMPARE_OPEN3D_ARGS passes options to tools/compare_open3d.py run (--frames,
# --rounds).
OPEN3D_DEBS          := python3-open3d python3-numpy
OPEN3D_MESHES        := build/scans/bunny.obj build/scans/dragon-48k.obj build/scans/dragon.obj build/bunny-dense.obj
COMPARE_OPEN3D_ARGS  ?=

.PHONY: compare-open3d deps-open3d

deps-open3d:
	@sh tools/deps.sh $(OPEN3D_DEBS)

build/open3d_ray_mask.so: tools/open3d_ray_mask.c
	@echo "  CC      $@"
	@mkdir -p $(dir $@)
	@$(CC) -std=c11 $(CFLAGS) -Wall -Wextra -shared -fPIC $< -o $@ -ldl

# The time of sr_pinhole_resolve, which `render --stats` leaves out.
build/pinhole_time: build/tools/pinhole_time.o $(call APP_LIBS,build)
	@echo "  LINK    $@"
	@$(CC) $(CFLAGS) $^ $(LIBS) -o $@

# The dense scan: the bunny after 4 Loop subdivisions, 940,544 triangles.
build/bunny-dense.obj: build/scans/bunny.obj tools/compare_open3d.py | deps-open3d
	/usr/bin/python3 tools/compare_open3d.py dense $< $@ 4

compare-open3d: deps deps-open3d build/softrast build/pinhole_time build/open3d_ray_mask.so $(OPEN3D_MESHES)
	LD_PRELOAD=$(CURDIR)/build/open3d_ray_mask.so /usr/bin/python3 tools/compare_open3d.py run \
	    --out build/open3d-compare.md $(COMPARE_OPEN3D_ARGS) $(OPEN3D_MESHES)

-include build/tools/pinhole_time.d
