# fuzz/fuzz.mk — libFuzzer targets (included by the Makefile; see fuzz/README.md).
#
#   make fuzz               each target for FUZZ_SECONDS (default 600), one after the other
#   make fuzz-smoke         the same for 20 s each (CI, make test)
#   make fuzz-regressions   replays every saved reproducer in fuzz/regressions/
#   make fuzz-clean         removes build/fuzz/ (binaries, scratch corpora, artifacts)
#
# The library is compiled again into build/fuzz/ with coverage instrumentation
# (-fsanitize=fuzzer-no-link) plus ASan and UBSan; only the targets link
# libFuzzer's main. Each run starts from the committed seeds in fuzz/corpus/T/
# copied into build/fuzz/corpus/T/, where libFuzzer also keeps what it finds:
# nothing is ever written into fuzz/corpus/ automatically. Any crash, sanitizer
# report, failed invariant, leak or timeout stops the run with a non-zero exit
# status and leaves the input in build/fuzz/artifacts/T/.

FUZZ_CC       ?= clang
FUZZ_SECONDS  ?= 600
FUZZ_TIMEOUT  ?= 10
FUZZ_TOLERATE ?=
FUZZ_TARGETS  := draw obj mesh
FUZZ_MAX_LEN_draw := 4096
FUZZ_MAX_LEN_obj  := 8192
FUZZ_MAX_LEN_mesh := 20000

FUZZ_PKG_CFLAGS = $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
FUZZ_PKG_LIBS   = $(shell pkg-config --libs $(PKGS) 2>/dev/null)
FUZZ_SANITIZE = address,undefined
FUZZ_CFLAGS = -std=c11 -D_POSIX_C_SOURCE=200809L -ffp-contract=off -g -O1 -fsanitize=$(FUZZ_SANITIZE) \
              -fno-sanitize-recover=all -fno-omit-frame-pointer -Iinclude -Isrc $(FUZZ_PKG_CFLAGS) -MMD -MP
FUZZ_WARN   = -Wall -Wextra -Werror -Wshadow -Wstrict-prototypes -Wno-missing-field-initializers

FUZZ_LIB_SRC := $(LIB_SRC)
FUZZ_LIB_OBJ := $(FUZZ_LIB_SRC:%.c=build/fuzz/%.o)
FUZZ_BINS    := $(FUZZ_TARGETS:%=build/fuzz/fuzz_%)

.PHONY: fuzz fuzz-smoke fuzz-build fuzz-regressions fuzz-clean

$(FUZZ_LIB_OBJ): build/fuzz/%.o: %.c
	@mkdir -p $(@D)
	@echo "  CC fuzz $<"
	@$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer-no-link -c $< -o $@

# fuzz_draw's parts besides its entry point (fuzz/draw_*.c).
FUZZ_DRAW_PARTS := $(patsubst fuzz/%.c,build/fuzz/%.o,$(wildcard fuzz/draw_*.c))

$(FUZZ_BINS:%=%.o) $(FUZZ_DRAW_PARTS): build/fuzz/%.o: fuzz/%.c
	@mkdir -p $(@D)
	@echo "  CC fuzz $<"
	@$(FUZZ_CC) $(FUZZ_CFLAGS) $(FUZZ_WARN) -fsanitize=fuzzer-no-link -c $< -o $@

build/fuzz/fuzz_draw: $(FUZZ_DRAW_PARTS)

$(FUZZ_BINS): build/fuzz/%: build/fuzz/%.o $(FUZZ_LIB_OBJ)
	@echo "  LINK    $@"
	@$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer $^ $(FUZZ_PKG_LIBS) -lm -lpthread -o $@

fuzz-build: $(FUZZ_BINS)

# Runs the targets in FUZZ_RUN one after the other: seeds copied over the
# scratch corpus, the log in build/fuzz/T.log, a summary line printed; the
# first failure stops with its log tail and reproducer.
FUZZ_RUN ?= $(FUZZ_TARGETS)

fuzz: fuzz-build
	@for t in $(FUZZ_RUN); do \
	   case $$t in draw) max=$(FUZZ_MAX_LEN_draw);; obj) max=$(FUZZ_MAX_LEN_obj);; mesh) max=$(FUZZ_MAX_LEN_mesh);; *) echo "no fuzz target $$t"; exit 1;; esac; \
	   rm -rf build/fuzz/artifacts/$$t && mkdir -p build/fuzz/corpus/$$t build/fuzz/artifacts/$$t; \
	   cp fuzz/corpus/$$t/* build/fuzz/corpus/$$t/; \
	   echo "  FUZZ    $$t for $(FUZZ_SECONDS) s (log: build/fuzz/$$t.log)"; \
	   FUZZ_TOLERATE=$(FUZZ_TOLERATE) ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	     ./build/fuzz/fuzz_$$t -max_total_time=$(FUZZ_SECONDS) -max_len=$$max -timeout=$(FUZZ_TIMEOUT) \
	     -print_final_stats=1 -artifact_prefix=build/fuzz/artifacts/$$t/ build/fuzz/corpus/$$t \
	     < /dev/null > build/fuzz/$$t.log 2>&1; status=$$?; \
	   last=$$(grep -E '^#[0-9]+' build/fuzz/$$t.log | tail -n 1); \
	   execs=$$(sed -n 's/^stat::number_of_executed_units: *//p' build/fuzz/$$t.log); \
	   echo "  fuzz_$$t: $${execs:-?} execs, corpus $$(ls build/fuzz/corpus/$$t | wc -l) files; last: $$last"; \
	   if [ $$status -ne 0 ]; then \
	     tail -n 60 build/fuzz/$$t.log; \
	     echo "fuzz_$$t: FAILED (exit $$status); reproducer: $$(ls build/fuzz/artifacts/$$t/* 2>/dev/null)"; \
	     exit 1; \
	   fi; \
	 done

fuzz-smoke: FUZZ_SECONDS = 20
fuzz-smoke: fuzz

# Each saved reproducer must now pass (libFuzzer runs a file argument once);
# prints one line per file and fails if any does.
fuzz-regressions: fuzz-build
	@failed=0; for t in $(FUZZ_TARGETS); do \
	   for f in fuzz/regressions/$$t/*; do \
	     [ -f "$$f" ] || continue; \
	     if FUZZ_TOLERATE=$(FUZZ_TOLERATE) ./build/fuzz/fuzz_$$t "$$f" > build/fuzz/regression.log 2>&1; then \
	       echo "  pass    $$f"; \
	     else \
	       echo "  FAIL    $$f: $$(grep -m1 -E 'invariant failed|runtime error|ERROR: AddressSanitizer' build/fuzz/regression.log)"; \
	       failed=1; \
	     fi; \
	   done; \
	 done; exit $$failed

fuzz-clean:
	rm -rf build/fuzz

-include $(FUZZ_LIB_OBJ:.o=.d) $(FUZZ_TARGETS:%=build/fuzz/fuzz_%.d) $(FUZZ_DRAW_PARTS:.o=.d)
