#!/bin/sh
# Proves that the per-frame code was built integer-only: the archive built
# with -mgeneral-regs-only holds one object per per-frame source, and none of
# its instructions touches a floating-point or vector register.
set -eu
archive=$1
expected_objects=$2
objdump=${OBJDUMP:-objdump}

objects=$(ar t "$archive" | grep -c '\.o$' || true)
if [ "$objects" -ne "$expected_objects" ]; then
    echo "FAIL: $archive holds $objects objects, expected $expected_objects"
    exit 1
fi

# objdump must know the architecture (the host's objdump cannot read an
# aarch64 archive: the cross build passes OBJDUMP); a failed disassembly
# must not pass as "no floating point found".
dis=$(mktemp)
trap 'rm -f "$dis"' EXIT
if ! $objdump -d --no-show-raw-insn "$archive" > "$dis"; then
    echo "FAIL: $objdump cannot disassemble $archive (set OBJDUMP for a cross build)"
    exit 1
fi
case "$($objdump -f "$archive" | grep -m1 'architecture:')" in
    *aarch64*) pattern='[[:space:],\[]([vqdsbh][0-9]{1,2})([,.[:space:]]|$)' ;;
    *) pattern='%(x|y|z)mm[0-9]|%st(\(|$|,)|\<(fld|fst|fild|fist|fadd|fmul|fdiv|fsub|fcom)[a-z]*\>' ;;
esac
# Branch targets ("b.ne d4 <f+0x44>") and comments are dropped first: an
# address such as d4 would read as a register.
if sed -e 's,//.*,,' -e 's,[0-9a-f]* <[^>]*>,,g' "$dis" | grep -E -n "$pattern" > "$dis.hits"; then
    echo "FAIL: floating-point or vector instructions in the per-frame code:"
    head -n 20 "$dis.hits"
    rm -f "$dis.hits"
    exit 1
fi
rm -f "$dis.hits"
echo "ok: $objects per-frame objects ($($objdump -f "$archive" | grep -m1 -o 'architecture: [^,]*')), no floating-point or vector registers"
