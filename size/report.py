#!/usr/bin/env python3
"""robowire's size report: build one minimal no_std binary per row, read the
sections and symbols from each ELF, print the table and fail when a row
exceeds its goal (unless it is a known miss still under its ceiling) or when a
binary links panic machinery it is not known to link.

Usage: python3 size/report.py [--no-build]

Flash is every allocated section with contents (vector table, .text,
.rodata, the initial image of .data); RAM rows are the size of a symbol.
Nothing here times anything.
"""
import os
import struct
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
V7 = "thumbv7em-none-eabihf"
V6 = "thumbv6m-none-eabi"

# (row, binary, target, measure, goal in bytes)
#   measure: "flash" (a size/ binary), "firmware" (examples/firmware) or
#   ("symbol", name) (the symbol's size in the binary: RAM).
ROWS = [
    ("OmniTiles command decoder, push/poll", "omnitiles_push", V7, "flash", 1024),
    ("OmniTiles command decoder, decode on a slice", "omnitiles_decode", V7, "flash", 1024),
    ("OmniTiles 53-byte telemetry encoder", "omnitiles_telemetry_encode", V7, "flash", 400),
    ("Telemetrix command decoder (Pico side)", "telemetrix_commands", V6, "flash", 1536),
    ("Pixy2 request decoder (camera side)", "pixy2_requests", V7, "flash", 1536),
    ("examples/firmware, total flash", "firmware", V7, "firmware", 3072),
    ("RAM of the commands-only OmniTiles decoder", "omnitiles_push", V7, ("symbol", "DECODER"), 32),
]

# Rows that do not meet their goal yet: the ceiling they must not grow past
# (so CI stays green while they are worked on, and fails if they regress)
# and what limits them.
KNOWN = {
    "OmniTiles command decoder, push/poll": (
        1950,
        "the byte path's candidate handling and parse (840 B), the resync verification (480 B with its confirmation), realignment and shifts",
    ),
    "OmniTiles command decoder, decode on a slice": (
        3950,
        "both paths (in place and buffered) inline into the caller's loop, the resync verification, memcpy for a frame cut by a chunk",
    ),
    "OmniTiles 53-byte telemetry encoder": (
        1650,
        "the layout-generic encoder (offset table, optional fields, range checks), memcpy and memclr",
    ),
    "Telemetrix command decoder (Pico side)": (
        7050,
        "the command parser (parse_command alone is 5.1 KB: the custom rows' parse code, one error path per checked field); no memcpy since Command's tag is word-sized",
    ),
    "Pixy2 request decoder (camera side)": (
        6200,
        "memmove and memcpy for its 144-byte buffer (2.3 KB), the request parser, the framing's sync search",
    ),
    "examples/firmware, total flash": (
        4350,
        "the engine and verification (as the push row), the telemetry encoder, cortex-m-rt",
    ),
    "RAM of the commands-only OmniTiles decoder": (
        72,
        "eight u32 counters (32 B), the 14-byte buffer the resync verification needs, three indices",
    ),
}

# Binaries known to link panic machinery still (the reason). Any other binary
# that links it fails the report.
PANICS_KNOWN: dict = {}

PANIC_MARKS = (
    b"panicking",
    b"panic_bounds_check",
    b"panic_fmt",
    b"slice_index",
    b"slice_start_index",
    b"slice_end_index",
    b"unwrap_failed",
    b"expect_failed",
    b"rust_begin_unwind",
    b"str_index_overflow",
)


def readable(name):
    """`core::panicking::panic_fmt` from a v0-mangled symbol (its identifiers
    joined by `::`); other names as they are."""
    if not name.startswith("_R"):
        return name
    parts, i = [], 2
    while i < len(name):
        if name[i].isdigit():
            j = i
            while j < len(name) and name[j].isdigit():
                j += 1
            n = int(name[i:j])
            if name[j:j + 1] == "_":
                j += 1
            parts.append(name[j:j + n])
            i = j + n
        elif name[i:i + 2] == "Cs":
            i = name.index("_", i) + 1  # the crate's disambiguator hash
        else:
            i += 1
    return "::".join(parts) or name


def elf(path):
    """Sections {name: (size, alloc, has_contents)} and symbols {name: size}
    of a 32-bit little-endian ELF."""
    data = open(path, "rb").read()
    if data[:4] != b"\x7fELF" or data[4] != 1 or data[5] != 1:
        sys.exit(f"{path}: not a 32-bit little-endian ELF")
    shoff, = struct.unpack_from("<I", data, 0x20)
    shentsize, shnum, shstrndx = struct.unpack_from("<HHH", data, 0x2E)
    headers = [struct.unpack_from("<IIIIIIIIII", data, shoff + i * shentsize) for i in range(shnum)]

    def string(table, offset):
        start = headers[table][4] + offset
        return data[start:data.index(b"\0", start)]

    sections, symbols = {}, {}
    for h in headers:
        name, kind, flags, _, offset, size, link = h[:7]
        sections[string(shstrndx, name).decode()] = (size, bool(flags & 2), kind != 8)
        if kind == 2:  # SHT_SYMTAB
            for at in range(offset, offset + size, 16):
                sym_name, _, sym_size = struct.unpack_from("<III", data, at)
                symbols[string(link, sym_name)] = sym_size
    return sections, symbols


def build():
    def cargo(*args, cwd):
        print("+ cargo " + " ".join(args), flush=True)
        subprocess.run(["cargo", *args], cwd=cwd, check=True)

    cargo("build", "--release", "--target", V7, cwd=HERE)
    cargo("build", "--release", "--target", V6, "--bin", "telemetrix_commands", cwd=HERE)
    cargo("build", "--release", cwd=os.path.join(ROOT, "examples", "firmware"))


def path_of(binary, target):
    if binary == "firmware":
        return os.path.join(ROOT, "examples", "firmware", "target", target, "release", "firmware")
    return os.path.join(HERE, "target", target, "release", binary)


def main():
    if "--no-build" not in sys.argv[1:]:
        build()
    failures, lines, panic_lines = [], [], []
    seen = set()
    header = f"| {'row':<46} | {'target':<21} | {'.text':>6} | {'.rodata':>7} | {'.data':>5} | {'.bss':>5} | {'size':>6} | {'goal':>5} | status"
    for row, binary, target, measure, goal in ROWS:
        sections, symbols = elf(path_of(binary, target))
        sec = lambda name: sections.get(name, (0, False, False))[0]
        if isinstance(measure, tuple):
            size = symbols.get(measure[1].encode())
            if size is None:
                sys.exit(f"{binary}: no symbol {measure[1]}")
        else:
            size = sum(s for s, alloc, contents in sections.values() if alloc and contents)
        if size <= goal:
            status = "ok"
            if row in KNOWN:
                status += " (now meets its goal: drop it from KNOWN)"
        elif row in KNOWN and size <= KNOWN[row][0]:
            status = f"known miss: {KNOWN[row][1]}"
        else:
            status = "FAIL"
            failures.append(f"{row}: {size} B > goal {goal} B" + (f" and ceiling {KNOWN[row][0]} B" if row in KNOWN else ""))
        cols = [sec(".text"), sec(".rodata"), sec(".data"), sec(".bss")]
        if isinstance(measure, tuple):
            cols = ["-"] * 4
        lines.append(
            f"| {row:<46} | {target:<21} | {cols[0]:>6} | {cols[1]:>7} | {cols[2]:>5} | {cols[3]:>5} | {size:>6} | {goal:>5} | {status}"
        )
        if (binary, target) in seen:
            continue
        seen.add((binary, target))
        found = sorted({readable(n.decode(errors="replace")) for n in symbols if any(m in n for m in PANIC_MARKS)})
        if not found:
            panic_lines.append(f"{binary} ({target}): no panic machinery linked")
            if binary in PANICS_KNOWN:
                panic_lines[-1] += " (now panic-free: drop it from PANICS_KNOWN)"
        elif binary in PANICS_KNOWN:
            panic_lines.append(f"{binary} ({target}): known: {PANICS_KNOWN[binary]}: {', '.join(found)}")
        else:
            panic_lines.append(f"{binary} ({target}): FAIL: links {', '.join(found)}")
            failures.append(f"{binary} links panic machinery: {', '.join(found)}")
    print("\nsize report (bytes; size = flash: every allocated section with contents, or RAM for the RAM row)")
    print(header)
    for line in lines:
        print(line)
    print("\npanic machinery")
    for line in panic_lines:
        print("  " + line)
    if failures:
        print("\nFAILED:")
        for failure in failures:
            print("  " + failure)
        sys.exit(1)
    print("\nsize report: every row within its goal or its known ceiling")


if __name__ == "__main__":
    main()
