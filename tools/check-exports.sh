#!/bin/sh
# Every symbol an installed softrast library exports must be declared SR_API
# in an installed header, and every SR_API declaration must be exported: the
# headers are the whole promise. Usage: check-exports.sh PREFIX
set -eu
prefix=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# Declared: the name before the first '(' of each SR_API declaration (which
# may wrap), or the last word of an SR_API variable.
grep -hv "^#" "$prefix"/include/softrast/*.h | tr '\n' ' ' | sed 's/;/;\n/g' | grep 'SR_API ' \
    | sed -e 's/.*SR_API //' -e 's/(.*//' -e 's/\[.*//' | awk '{ print $NF }' | tr -d '*' | sort -u > "$tmp/declared"
status=0
for lib in "$prefix"/lib/libsoftrast*.a; do
    nm -g --defined-only "$lib" | awk 'NF == 3 { print $3 }' | sort -u > "$tmp/exported"
    extra=$(comm -23 "$tmp/exported" "$tmp/declared")
    if [ -n "$extra" ]; then
        echo "$(basename "$lib") exports what no public header declares:" $extra >&2
        status=1
    fi
    cat "$tmp/exported" >> "$tmp/all"
done
sort -u "$tmp/all" -o "$tmp/all"
missing=$(comm -13 "$tmp/all" "$tmp/declared")
if [ -n "$missing" ]; then
    echo "declared SR_API but exported by no library:" $missing >&2
    status=1
fi
[ $status -eq 0 ] && echo "exports: $(wc -l < "$tmp/all") symbols, each declared in include/softrast/"
exit $status
