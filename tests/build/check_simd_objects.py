#!/usr/bin/env python3
"""Proves that every SIMD row kernel variant (src/algo/simd/) was built with
vector instructions of its kind, so that a variant whose vectorisation was
lost (an optimisation level, a missing target flag, a compiler that ignores
a pragma) fails here with its name instead of running as slow scalar code.

Each archive holds the objects of src/algo/simd/: NAME_x86.c holds x86
variants, NAME_neon.c aarch64 NEON ones, and each compiles to nothing on
the other CPU family. Every global function of a variant object is a
variant named after its instruction set (rte_..._sse2, _ssse3, _sse41,
_avx2, _avx512, _neon) and is disassembled on its own (objdump -d, split by symbol,
with the static functions of its object that it calls) and must hold:

  sse2   packed instructions on xmm registers, nothing past SSE2
         (no VEX encoding, no ymm/zmm, no SSSE3 or SSE4 instructions)
  ssse3  the same with at least one SSSE3 instruction (pshufb, pmaddubsw,
         ...), nothing past SSSE3
  sse41  the same with at least one SSE4.1 instruction, nothing past SSE4.1
  avx2   packed integer (vp...) instructions on ymm registers, no AVX-512
         (zmm or mask registers)
  avx512 packed integer (vp...) instructions on zmm registers
  neon   arithmetic on vector registers with an arrangement (v0.16b,
         v1.8h, ...; loads, stores and moves do not count), no SVE

The "nothing past" rules matter as much as the vector ones: the dispatch
runs an SSSE3 variant on CPUs without AVX, where a VEX instruction faults.

usage: check_simd_objects.py [--cross] CPU_FAMILY OBJDUMP ARCHIVE COUNT [ARCHIVE COUNT]...
CPU_FAMILY is meson's host_machine.cpu_family(); COUNT the number of
sources (objects) the archive must hold. With --cross (a cross build), an
objdump that is missing or cannot read the archives skips the test (exit
77) with the reason; in a native build that fails it."""
import re
import subprocess
import sys

SKIP = 77
X86_FAMILIES = ('x86', 'x86_64')
FILE_FAMILY = {'_x86': 'x86', '_neon': 'aarch64'}
VARIANT_SUFFIXES = {'_sse2': 'sse2', '_ssse3': 'ssse3', '_sse41': 'sse41', '_avx2': 'avx2',
                    '_avx512': 'avx512', '_neon': 'neon'}
ISA_FAMILY = {'sse2': 'x86', 'ssse3': 'x86', 'sse41': 'x86', 'avx2': 'x86', 'avx512': 'x86',
              'neon': 'aarch64'}

SSSE3_MNEMONICS = {'pshufb', 'pmaddubsw', 'palignr', 'pabsb', 'pabsw', 'pabsd', 'phaddw', 'phaddd',
                   'phaddsw', 'phsubw', 'phsubd', 'phsubsw', 'pmulhrsw', 'psignb', 'psignw',
                   'psignd'}
SSE41_MNEMONICS = {'pmulld', 'pmuldq', 'pminsb', 'pminsd', 'pminuw', 'pminud', 'pmaxsb', 'pmaxsd',
                   'pmaxuw', 'pmaxud', 'pblendvb', 'pblendw', 'blendps', 'blendpd', 'blendvps',
                   'blendvpd', 'ptest', 'pextrb', 'pextrd', 'pextrq', 'pinsrb', 'pinsrd', 'pinsrq',
                   'packusdw', 'pcmpeqq', 'roundps', 'roundpd', 'roundss', 'roundsd', 'dpps',
                   'dppd', 'mpsadbw', 'phminposuw', 'extractps', 'insertps', 'movntdqa',
                   'pmovzxbw', 'pmovzxbd', 'pmovzxbq', 'pmovzxwd', 'pmovzxwq', 'pmovzxdq',
                   'pmovsxbw', 'pmovsxbd', 'pmovsxbq', 'pmovsxwd', 'pmovsxwq', 'pmovsxdq'}
SSE42_MNEMONICS = {'pcmpgtq', 'pcmpestri', 'pcmpestrm', 'pcmpistri', 'pcmpistrm', 'crc32'}
# Beyond each SSE level: instructions of the later levels.
SSE_BEYOND = {'sse2': SSSE3_MNEMONICS | SSE41_MNEMONICS | SSE42_MNEMONICS,
              'ssse3': SSE41_MNEMONICS | SSE42_MNEMONICS,
              'sse41': SSE42_MNEMONICS}
SSE_NEEDS = {'sse2': None, 'ssse3': SSSE3_MNEMONICS, 'sse41': SSE41_MNEMONICS}
# Packed (p...) instructions that only move data in or out of a register.
X86_MOVES = ('pinsr', 'pextr', 'pbroadcast', 'perm2f128', 'permil')
NEON_MOVES = {'ld1', 'ld2', 'ld3', 'ld4', 'ld1r', 'ld2r', 'ld3r', 'ld4r', 'st1', 'st2', 'st3',
              'st4', 'ldr', 'str', 'ldp', 'stp', 'ldur', 'stur', 'ldnp', 'stnp', 'mov', 'movi',
              'mvni', 'dup', 'ins', 'umov', 'smov', 'fmov'}

X86_REG = re.compile(r'%([xyz]mm\d+|k[0-7])\b')
NEON_VREG = re.compile(r'\bv\d{1,2}\.\d*[bhsdq]\b')
SVE_REG = re.compile(r'\bz\d{1,2}\.[bhsdq]\b|\bp\d{1,2}/[mz]\b')


def fail(msg):
    print('FAIL: ' + msg)
    return 1


def objdump(tool, args, archive):
    """objdump's output, or None (with stderr shown) when it fails."""
    try:
        run = subprocess.run([tool] + args + [archive], capture_output=True, text=True)
    except OSError as e:
        print(f'{tool}: {e}')
        return None
    if run.returncode != 0:
        print(run.stderr.strip())
        return None
    return run.stdout


def split_members(text):
    """{member: [lines]} of objdump's output for an archive."""
    members, lines = {}, None
    for line in text.splitlines():
        m = re.match(r'^(\S+\.o):\s+file format (\S+)$', line)
        if m:
            lines = members.setdefault(m.group(1), [])
        elif lines is not None:
            lines.append(line)
    return members


def functions_of(symbol_lines):
    """{name: is_global} of the function symbols of one member (objdump -t)."""
    functions = {}
    for line in symbol_lines:
        m = re.match(r'^[0-9a-f]+ (.{7}) \S+\s+[0-9a-f]+\s+(?:\.hidden\s+)?(\S+)$', line)
        if m and m.group(1)[6] == 'F':
            functions[m.group(2)] = m.group(1)[0] in 'gu'
    return functions


def disassembly_of(dis_lines):
    """{symbol: ([(mnemonic, operands)], {referenced symbols})} of one
    member (objdump -d -r --no-show-raw-insn). Comments are dropped; the
    <symbol+offset> of branch targets and relocations give the references."""
    bodies, current = {}, None
    for line in dis_lines:
        m = re.match(r'^[0-9a-f]+ <(.+)>:$', line)
        if m:
            current = bodies.setdefault(m.group(1), ([], set()))
            continue
        if current is None:
            continue
        m = re.match(r'^\s+[0-9a-f]+: (R_\S+)\s+(\S+)$', line)
        if m:
            current[1].add(re.split(r'[-+]0x', m.group(2))[0])
            continue
        m = re.match(r'^\s+[0-9a-f]+:\t(\S+)\s*(.*)$', line)
        if m:
            # comments: x86 "# 1e <f+0x1e>", aarch64 "// #12" (not "#12" immediates)
            ops = re.sub(r'\s*(//|# ).*$', '', m.group(2))
            for target in re.findall(r'<([^>+]+)(?:\+0x[0-9a-f]+)?>', ops):
                current[1].add(target)
            current[0].append((m.group(1), re.sub(r'[0-9a-f]+ <[^>]*>', '', ops)))
    return bodies


def body_with_callees(name, bodies, functions):
    """The instructions of `name` and of the static functions of its object
    that it reaches (the compiler may leave a loop in a local clone)."""
    seen, todo, insns = set(), [name], []
    while todo:
        sym = todo.pop()
        if sym in seen or sym not in bodies:
            continue
        seen.add(sym)
        insns += bodies[sym][0]
        todo += [r for r in bodies[sym][1] if r in functions and not functions[r]]
    return insns


def x86_packed(mnemonic, ops, reg_class):
    """Whether this is a packed (vector) operation on registers of
    reg_class ('xmm', 'ymm' or 'zmm'), not a move or a zeroing idiom."""
    regs = X86_REG.findall(ops)
    if not any(r.startswith(reg_class) for r in regs):
        return False
    base = mnemonic[1:] if mnemonic.startswith('v') else mnemonic
    if any(base.startswith(p) for p in X86_MOVES):
        return False
    if base.startswith(('pxor', 'pcmpeq', 'psub', 'xorp')) and len(set(regs)) == 1:
        return False
    return base.startswith('p') or base.endswith(('ps', 'pd'))


def check_x86(isa, insns):
    """(error or None, summary) of one x86 variant's instructions."""
    if isa == 'avx2':
        past = [f'{m} {o}' for m, o in insns if re.search(r'%(zmm\d+|k[0-7])\b|\{', o)]
        if past:
            return f'AVX-512 in an AVX2 variant: {past[0]}', ''
        n = sum(1 for m, o in insns if m.startswith('vp') and x86_packed(m, o, 'ymm'))
        if n == 0:
            return 'no packed integer instruction on ymm registers (not vectorised for AVX2)', ''
        return None, f'{n} packed integer instructions on ymm'
    if isa == 'avx512':
        n = sum(1 for m, o in insns if m.startswith('vp') and x86_packed(m, o, 'zmm'))
        if n == 0:
            return 'no packed integer instruction on zmm registers (not vectorised for AVX-512)', ''
        return None, f'{n} packed integer instructions on zmm'
    for m, o in insns:
        regs = X86_REG.findall(o)
        if m in ('vzeroupper', 'vzeroall') or (m.startswith('v') and regs):
            return f'VEX (AVX) instruction in an {isa} variant: {m} {o}', ''
        if any(not r.startswith('xmm') for r in regs):
            return f'register past {isa}: {m} {o}', ''
        if m in SSE_BEYOND[isa]:
            return f'instruction past {isa}: {m} {o}', ''
    n = sum(1 for m, o in insns if x86_packed(m, o, 'xmm'))
    if n == 0:
        return 'no packed instruction on xmm registers (not vectorised)', ''
    needs = SSE_NEEDS[isa]
    if needs is not None:
        used = sorted({m for m, _ in insns if m in needs})
        if not used:
            return f'packed code but no {isa} instruction (as SSE2 code it needs no {isa})', ''
        return None, f'{n} packed instructions on xmm, {isa}: {" ".join(used)}'
    return None, f'{n} packed instructions on xmm'


def check_neon(insns):
    sve = [f'{m} {o}' for m, o in insns if SVE_REG.search(o)]
    if sve:
        return f'SVE in a NEON variant: {sve[0]}', ''
    n = sum(1 for m, o in insns if m not in NEON_MOVES and NEON_VREG.search(o))
    if n == 0:
        return 'no arithmetic on vector registers (not vectorised for NEON)', ''
    return None, f'{n} vector instructions on v registers'


def check_member(member, cpu, functions, bodies):
    """Errors of one object; prints a line for each variant."""
    errors = 0
    stem = re.sub(r'\.c(pp)?\.o(bj)?$', '', member)
    family = next((f for s, f in FILE_FAMILY.items() if stem.endswith(s)), None)
    if family is None:
        return fail(f'{member}: the name ends in neither _x86 nor _neon (which CPU is it for?)')
    variants = sorted(name for name, is_global in functions.items() if is_global)
    if family != cpu:
        if functions:
            errors += fail(f'{member}: {family} source compiled to functions on {cpu}: '
                           + ' '.join(sorted(functions)))
        else:
            print(f'ok   {member}: empty on {cpu} (an {family} source)')
        return errors
    if not variants:
        return fail(f'{member}: no variant function on {cpu} (compiled to nothing?)')
    for name in variants:
        isa = next((i for s, i in VARIANT_SUFFIXES.items() if name.endswith(s)), None)
        if isa is None or ISA_FAMILY[isa] != cpu:
            errors += fail(f'{name} ({member}): not named after a {cpu} instruction set '
                           f'({", ".join(s for s, i in VARIANT_SUFFIXES.items() if ISA_FAMILY[i] == cpu)})')
            continue
        insns = body_with_callees(name, bodies, functions)
        error, summary = check_x86(isa, insns) if cpu == 'x86' else check_neon(insns)
        if error:
            errors += fail(f'{isa:6} {name} ({member}): {error}')
        else:
            print(f'ok   {isa:6} {name} ({member}): {summary}')
    return errors


def main(argv):
    cross = '--cross' in argv
    args = [a for a in argv if a != '--cross']
    if len(args) < 4 or len(args) % 2:
        print(__doc__)
        return 2
    cpu = 'x86' if args[0] in X86_FAMILIES else args[0]
    tool = args[1]
    if cpu not in ('x86', 'aarch64'):
        print(f'SKIP: no SIMD variants for CPU family {args[0]}')
        return SKIP
    archives = list(zip(args[2::2], (int(n) for n in args[3::2])))
    if not tool:
        why = 'no objdump for the host machine (set objdump in the cross file)'
        print(('SKIP: ' if cross else 'FAIL: ') + why)
        return SKIP if cross else 1
    errors = checked = 0
    for archive, count in archives:
        header = objdump(tool, ['-f'], archive)
        arch = re.search(r'architecture: ([^,\s]+)', header or '')
        if header is None or arch is None or ('aarch64' in arch.group(1)) != (cpu == 'aarch64'):
            why = (f'{tool} cannot disassemble {archive} for {cpu}'
                   + (f' (it reads {arch.group(1)})' if arch else ''))
            print(('SKIP: ' if cross else 'FAIL: ') + why)
            return SKIP if cross else 1
        symbols = split_members(objdump(tool, ['-t'], archive) or '')
        disassembly = split_members(objdump(tool, ['-d', '-r', '--no-show-raw-insn'], archive) or '')
        if len(symbols) != count:
            errors += fail(f'{archive} holds {len(symbols)} objects, expected {count}')
        for member in sorted(symbols):
            functions = functions_of(symbols[member])
            errors += check_member(member, cpu, functions,
                                   disassembly_of(disassembly.get(member, [])))
            checked += sum(1 for f, g in functions.items() if g)
    print(f'{"FAIL" if errors else "ok"}: {checked} variant functions on {cpu}, {errors} errors')
    return 1 if errors else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
