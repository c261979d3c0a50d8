#!/usr/bin/env python3
"""check-san-log.py LOG — fails (exit 1) when the sanitisers' log of a test
run reports an error: any UBSan "runtime error:", any AddressSanitizer
error, and any leak with a frame of softrast's. A leak whose every frame
after the allocator is inside libcriterion is the test runner's own (its
parent process, which softrast's code never runs in) and is only named."""
import re
import sys

text = "\n" + open(sys.argv[1], errors="replace").read()
bad = "runtime error:" in text or "ERROR: AddressSanitizer" in text
for block in re.split(r"\n(?=(?:Direct|Indirect) leak of )", text)[1:]:
    frames = re.findall(r"^\s+#(\d+) 0x[0-9a-f]+ (.*)$", block.split("\n\n")[0], re.M)
    own = [f for n, f in frames if n != "0"]
    if own and all("libcriterion.so" in f for f in own):
        print("note: a leak inside libcriterion alone (the test runner's), tolerated:", block.splitlines()[0])
    else:
        bad = True
if bad:
    print("sanitiser errors above")
sys.exit(1 if bad else 0)
