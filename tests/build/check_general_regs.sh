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

case "$($objdump -f "$archive" | grep -m1 'architecture:')" in
    *aarch64*) pattern='[[:space:],\[]([vqdsbh][0-9]{1,2})([,.[:space:]]|$)' ;;
    *) pattern='%(x|y|z)mm[0-9]|%st(\(|$|,)|\<(fld|fst|fild|fist|fadd|fmul|fdiv|fsub|fcom)[a-z]*\>' ;;
esac
if $objdump -d --no-show-raw-insn "$archive" | grep -E -n "$pattern" > /tmp/general-regs.$$ ; then
    echo "FAIL: floating-point or vector instructions in the per-frame code:"
    head -n 20 /tmp/general-regs.$$
    rm -f /tmp/general-regs.$$
    exit 1
fi
rm -f /tmp/general-regs.$$
echo "ok: $objects per-frame objects, no floating-point or vector registers"
