#!/usr/bin/env python3
"""Write the seed corpus (fuzz/corpus/<target>/seed-*) from the OmniTiles golden vectors."""
import os

HERE = os.path.dirname(os.path.abspath(__file__))

COMMANDS = """a5 50 50|a5 30 c8 f8|a5 30 ff 2f|a5 31 ff 30|a5 40 c8 08|a5 41 c8 09|a5 30 00 30|
a5 32 32|a5 42 42|a5 33 80 b3|a5 43 00 43|a5 70 0a fb 14 89|a5 70 1e 00 00 8e|a5 70 00 e2 00 52|
a5 70 80 7f 00 6f|a5 70 a5 00 00 15|a5 71 71"""
TELEMETRY = [
    "a5 60 d0 07 e8 03 22",
    "a5 60 d0 07 e8 03 dc 05 c4 09 ff ff b8 0b 91",
    "a5 60 d0 07 e8 03 dc 05 c4 09 ac 0d 94 11 41 01 70",
    "a5 60 d0 07 e8 03 dc 05 c4 09 ac 0d 94 11 41 01 cd cc cc 3d cd cc 4c 3e cd cc 1c 41 "
    "0a d7 23 3c 0a d7 a3 bc 8f c2 f5 3c d1 07 d2 07 d3 07 d4 07 e9 03 ea 03 6c",
]

def h(s):
    return bytes.fromhex(s.replace("|", " ").replace("\n", " "))

commands = [h(c) for c in COMMANDS.replace("\n", "").split("|")]
telemetry = [h(t) for t in TELEMETRY]
brake_buffer = h("a5 32 32 a5 42 42") + bytes(122)
mixed = b"\x00\xff\xa5" + b"".join(c + b"\xa5\x13" for c in commands) + telemetry[3] + h("a5 60 00") + telemetry[3]
all_telemetry = b"".join(telemetry) + telemetry[0] + telemetry[3]

# Framing selectors: bit 0 commands, bits 1..5 layouts 7, 15, 17, 45, 53.
COMMANDS_ONLY, ANY, BLE53, ALL = 0x01, 0x2F, 0x20, 0x3F

def write(target, name, data):
    d = os.path.join(HERE, "corpus", target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, "seed-" + name), "wb") as f:
        f.write(data)

for sel, sel_name in [(COMMANDS_ONLY, "commands"), (ANY, "any"), (BLE53, "ble53"), (ALL, "all")]:
    for data, data_name in [(mixed, "mixed"), (all_telemetry, "telemetry"), (b"".join(commands), "commands"), (brake_buffer, "brake")]:
        # selector, 3 chunk sizes, stream
        write("omnitiles_stream", f"{sel_name}-{data_name}", bytes([sel, 3, 1, 7, 53]) + data)
        write("omnitiles_roundtrip", f"{sel_name}-{data_name}", bytes([sel]) + data)
    datagrams = b"".join(bytes([len(d)]) + d for d in telemetry + commands[:4] + [brake_buffer, b"".join(commands[:3])])
    write("omnitiles_datagram", sel_name, bytes([sel]) + datagrams)
for i, t in enumerate(telemetry):
    write("omnitiles_structured", f"telemetry{i}", bytes([1, 0x2F, 7]) + t)
write("omnitiles_structured", "commands", bytes([1, 0x20, 3]) + b"".join(commands))
