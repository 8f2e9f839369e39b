#!/usr/bin/env python3
"""An OmniTiles host loop on asyncio, against a simulated tile on a pseudo-terminal.

The shape an OmniTiles SDK user writes: open the tile's serial port, read
whatever bytes have arrived, hand them to robowire's decoder, act on each
telemetry frame, and send commands back. No hardware: a simulated tile runs
on the other end of a pty. It streams 53-byte BLE telemetry (some of it split
across writes, with a stray byte and a corrupted frame thrown in, as a real
link does) and obeys the host's commands, which it decodes with robowire
too.

    python python/examples/omnitiles_host.py [--frames 200] [--rate 400]

It exits 0 when the host saw every good frame, in order, and the tile every
command; otherwise 1.
"""

from __future__ import annotations

import argparse
import asyncio
import os
import sys
import tty
from robowire import Item, Stats, omnitiles


class SimulatedTile:
    """A tile on the master side of a pty: telemetry out, commands in."""

    def __init__(self, fd: int, frames: int, rate: float) -> None:
        self.fd = fd
        self.frames = frames
        self.period = 1.0 / rate
        self.m1_pos = 1000
        self.m1_speed = 0
        self.commands: list[Item] = []
        self.decoder = omnitiles.Decoder(source="host")

    def telemetry(self, n: int) -> bytes:
        return omnitiles.encode(
            {
                "type": "telemetry",
                "layout": "ble53",
                "m1_pos": self.m1_pos,
                "m2_pos": 2048,
                "uwb": [1500 + n, 2500, None, 3000],
                "tof": 321,
                "imu": {"ax": 0.1, "ay": 0.2, "az": 9.8, "gx": 0.01, "gy": -0.02, "gz": 0.03},
                "m1_adcs": [2001, 2002, 2003, 2004],
                "m2_adcs": [1001, 1002],
            }
        )

    def on_readable(self) -> None:
        """Commands from the host: decode them as the tile's firmware does."""
        try:
            data = os.read(self.fd, 4096)
        except OSError:
            return
        for command in self.decoder.feed(data):
            self.commands.append(command)
            if command.type == "m1_extend":
                self.m1_speed = command.speed // 50
            elif command.type == "m1_brake":
                self.m1_speed = 0

    async def run(self) -> None:
        loop = asyncio.get_running_loop()
        loop.add_reader(self.fd, self.on_readable)
        try:
            for n in range(self.frames):
                self.m1_pos = min(self.m1_pos + self.m1_speed, 4095)
                frame = self.telemetry(n)
                if n == 10:
                    os.write(self.fd, b"\x00")  # a stray byte on the line
                if n == 20:
                    corrupt = bytearray(frame)
                    corrupt[30] ^= 0x40  # a bit flipped in transit: the checksum fails
                    os.write(self.fd, bytes(corrupt))
                if n % 7 == 3:
                    os.write(self.fd, frame[:20])  # one frame in two writes
                    await asyncio.sleep(self.period / 2)
                    os.write(self.fd, frame[20:])
                else:
                    os.write(self.fd, frame)
                await asyncio.sleep(self.period)
        finally:
            loop.remove_reader(self.fd)


async def host(port: str, frames: int) -> tuple[list[omnitiles.Telemetry], Stats]:
    """The host: read the port, decode telemetry, steer motor 1."""
    loop = asyncio.get_running_loop()
    fd = os.open(port, os.O_RDWR | os.O_NOCTTY)
    tty.setraw(fd)  # bytes as they are: no echo, no newline translation
    reader = asyncio.StreamReader()
    read_file = os.fdopen(fd, "rb", buffering=0, closefd=False)
    transport, _ = await loop.connect_read_pipe(lambda: asyncio.StreamReaderProtocol(reader), read_file)

    # Typed items: one light object per frame, fields as attributes.
    decoder = omnitiles.Decoder(source="tile", layouts=["ble53"])
    seen: list[omnitiles.Telemetry] = []
    extended = braked = False
    try:
        while len(seen) < frames:
            data = await asyncio.wait_for(reader.read(4096), timeout=5)
            for telemetry in decoder.feed(data):
                seen.append(telemetry)
                # Extend motor 1 after five frames, brake it once it has moved 20.
                if not extended and len(seen) >= 5:
                    os.write(fd, omnitiles.encode({"type": "m1_extend", "speed": 200}))
                    extended = True
                # m1_pos is None when the tile reports no reading (0xFFFF).
                elif extended and not braked and (telemetry.m1_pos or 0) >= 1020:
                    os.write(fd, omnitiles.encode({"type": "m1_brake"}))
                    braked = True
    finally:
        transport.close()
        os.close(fd)
    return seen, decoder.stats


async def main() -> int:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("--frames", type=int, default=200, help="telemetry frames the tile sends")
    parser.add_argument("--rate", type=float, default=400.0, help="frames per second (a tile sends up to 40)")
    args = parser.parse_args()

    master, slave = os.openpty()
    tty.setraw(master)
    port = os.ttyname(slave)
    tile = SimulatedTile(master, args.frames, args.rate)
    try:
        (seen, stats), _ = await asyncio.gather(host(port, args.frames), tile.run())
    finally:
        os.close(slave)
        os.close(master)

    positions = [t.m1_pos for t in seen if t.m1_pos is not None]
    print(f"host: {len(seen)} telemetry frames from {port}; m1_pos {positions[0]} -> {max(positions)}")
    print(f"host: first frame {seen[0]}")
    print(f"host: stats {stats}")
    print(f"tile: commands {[c.type for c in tile.commands]}")
    ok = (
        len(seen) == args.frames
        and [t.uwb[0] if t.uwb else None for t in seen] == [1500 + n for n in range(args.frames)]
        and seen[0].imu is not None  # the 53-byte layout carries the IMU
        and seen[0].imu.az == 9.800000190734863  # 9.8 as the wire's f32 carries it
        and stats["checksum_failures"] == 1
        and [c.type for c in tile.commands] == ["m1_extend", "m1_brake"]
    )
    print("ok" if ok else "FAILED")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(asyncio.run(main()))
