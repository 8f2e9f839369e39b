#!/usr/bin/env python3
"""Live decode through the Foxglove WebSocket server: frames per second to one
subscribed client, frames dropped, the lag from receive to the client, and the
decode's memory over the run.

    python3 benches/cli_live.py [--rate HZ] [--seconds S] [--bin PATH]

Plays a tile on a pseudo-terminal: the bytes of tests/data/ble_telemetry.bin
(53-byte telemetry with its line noise), 53 bytes every 1/HZ s (default 50 Hz,
a tile's rate), or as fast as the pseudo-terminal takes them with --rate 0.
`robowire decode omnitiles --port PTY --layout ble53 --foxglove 0 --format
mcap -o FILE` reads it and records at the same time; a WebSocket client
written here (the published ws-protocol, subprotocol foxglove.sdk.v1)
subscribes to /omnitiles/telemetry. After S seconds the decode is stopped with
SIGTERM and the script prints: frames the decode counted and the client
received, frames/s, the lag (client's wall clock at receipt minus the
message's log time, which is the decode's receive time on the Unix clock) as
median, 99th percentile and maximum, and the decode's resident memory sampled
every tenth of the run. Needs the binary built with --features
cli,cli-foxglove (built here unless --bin is given). Stdlib only; Linux.
"""

import argparse
import base64
import json
import os
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time
import tty

from release_binary import release_binary

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FRAME = 53


class Client:
    """The client half of RFC 6455 that a subscriber needs: the upgrade, the
    server's unmasked frames, and masked text frames of our own."""

    def __init__(self, port):
        self.sock = socket.create_connection(("127.0.0.1", port))
        key = base64.b64encode(os.urandom(16)).decode()
        self.sock.sendall(
            (
                f"GET / HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nUpgrade: websocket\r\n"
                f"Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\n"
                "Sec-WebSocket-Version: 13\r\nSec-WebSocket-Protocol: foxglove.sdk.v1\r\n\r\n"
            ).encode()
        )
        self.buf = b""
        while b"\r\n\r\n" not in self.buf:
            self.buf += self.sock.recv(4096)
        head, self.buf = self.buf.split(b"\r\n\r\n", 1)
        if b" 101 " not in head.split(b"\r\n")[0]:
            sys.exit(f"no WebSocket upgrade: {head!r}")

    def _need(self, n):
        while len(self.buf) < n:
            chunk = self.sock.recv(1 << 16)
            if not chunk:
                raise EOFError
            self.buf += chunk

    def read(self):
        """The next message: (opcode, payload)."""
        self._need(2)
        opcode, length = self.buf[0] & 0x0F, self.buf[1] & 0x7F
        start = 2
        if length == 126:
            self._need(4)
            length, start = struct.unpack_from(">H", self.buf, 2)[0], 4
        elif length == 127:
            self._need(10)
            length, start = struct.unpack_from(">Q", self.buf, 2)[0], 10
        self._need(start + length)
        payload, self.buf = self.buf[start : start + length], self.buf[start + length :]
        return opcode, payload

    def send_text(self, text):
        data, mask = text.encode(), os.urandom(4)
        header = bytes([0x81])
        header += bytes([0x80 | len(data)]) if len(data) < 126 else bytes([0xFE]) + struct.pack(">H", len(data))
        self.sock.sendall(header + mask + bytes(b ^ mask[i % 4] for i, b in enumerate(data)))


def rss_kib(pid):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rate", type=float, default=50.0, help="frames a second, 0 for flat out")
    parser.add_argument("--seconds", type=float, default=60.0)
    parser.add_argument("--bin", help="a robowire binary built with cli,cli-foxglove")
    options = parser.parse_args()

    binary = release_binary(options.bin, "cli,cli-foxglove")
    with open(os.path.join(ROOT, "tests", "data", "ble_telemetry.bin"), "rb") as f:
        capture = f.read()

    master, slave = os.openpty()
    tty.setraw(slave)
    device = os.ttyname(slave)
    scratch = tempfile.mkdtemp(prefix="robowire-live-bench-")
    recording = os.path.join(scratch, "live.mcap")
    decode = subprocess.Popen(
        [binary, "decode", "omnitiles", "--port", device, "--layout", "ble53",
         "--foxglove", "0", "--format", "mcap", "-o", recording],
        stderr=subprocess.PIPE,
        text=True,
    )
    banner = ""
    while "ws://" not in banner:  # the port line comes first, then the server's
        banner = decode.stderr.readline()
        if not banner:
            sys.exit("the decode stopped before its server started")
    port = int(banner.split("ws://127.0.0.1:")[1].split()[0])
    client = Client(port)
    # A channel is advertised with its first frame (its schema comes from it):
    # the capture's first 53 bytes are one frame, which the client misses.
    os.write(master, capture[:FRAME])
    channel = None
    while channel is None:
        opcode, payload = client.read()
        if opcode == 1:
            message = json.loads(payload)
            if message.get("op") == "advertise":
                for advertised in message["channels"]:
                    if advertised["topic"] == "/omnitiles/telemetry":
                        channel = advertised["id"]
    client.send_text(json.dumps({"op": "subscribe", "subscriptions": [{"id": 1, "channelId": channel}]}))
    time.sleep(0.2)  # the subscription reaches the server before the first frame

    stop = threading.Event()
    written = [FRAME]

    def play():
        # The tile: the capture's bytes, 53 at a time on the tile's period, or
        # flat out (a write blocks while the pseudo-terminal is full).
        period = 1.0 / options.rate if options.rate > 0 else 0.0
        at, next_due = FRAME, time.monotonic()
        while not stop.is_set():
            piece = capture[at : at + FRAME] if period else capture
            at = (at + FRAME) % len(capture) if period else 0
            os.write(master, piece)
            written[0] += len(piece)
            if period:
                next_due += period
                time.sleep(max(0.0, next_due - time.monotonic()))

    samples = []

    def sample():
        while not stop.wait(options.seconds / 10):
            samples.append(rss_kib(decode.pid))

    lags, received = [], [0]

    def receive():
        try:
            while True:
                opcode, payload = client.read()
                if opcode == 2 and payload[0] == 0x01:
                    now = time.time_ns()
                    log_time = struct.unpack_from("<Q", payload, 5)[0]
                    received[0] += 1
                    lags.append(now - log_time)
        except (EOFError, OSError):
            pass

    threads = [threading.Thread(target=f, daemon=True) for f in (play, sample, receive)]
    start = time.monotonic()
    for thread in threads:
        thread.start()
    time.sleep(options.seconds)
    stop.set()
    time.sleep(0.5)  # the last frames reach the client
    elapsed = time.monotonic() - start
    decode.send_signal(signal.SIGTERM)
    rest = decode.stderr.read()
    decode.wait()
    os.close(master)
    os.close(slave)
    summary = [line for line in rest.splitlines() if " frames," in line]
    frames = int(summary[0].split("robowire: ")[1].split(" frame")[0]) if summary else -1
    lags.sort()
    mib = [s / 1024 for s in samples]
    rate = "flat out" if options.rate <= 0 else f"{options.rate:g} Hz"
    print(f"{elapsed:.0f} s at {rate}: {written[0]} bytes written, {frames} frames decoded, "
          f"{received[0]} received by the client after its subscription to the first "
          f"({frames - 1 - received[0]} dropped), "
          f"{received[0] / elapsed:,.0f} frames/s")
    if lags:
        pick = lambda q: lags[min(len(lags) - 1, int(q * len(lags)))] / 1e6  # noqa: E731
        print(f"lag receive -> client: median {pick(0.5):.2f} ms, p99 {pick(0.99):.2f} ms, "
              f"max {lags[-1] / 1e6:.2f} ms")
    if mib:
        print(f"decode RSS (MiB, every {options.seconds / 10:.0f} s): "
              + " ".join(f"{m:.1f}" for m in mib))
    print(f"recording: {os.path.getsize(recording)} bytes (exit status {decode.returncode})")
    os.remove(recording)
    os.rmdir(scratch)


if __name__ == "__main__":
    main()
