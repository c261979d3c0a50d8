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
