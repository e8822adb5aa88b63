#!/usr/bin/env python3
"""Plays systemd's side of sd_notify: binds a unix datagram socket (a path, or '@name' for the
abstract namespace) and writes each message received, one per line, to a file, until
STOPPING=1 arrives or the time limit passes. Usage: SOCKET OUTPUT SECONDS"""
import socket
import sys
import time

address, output, seconds = sys.argv[1], sys.argv[2], float(sys.argv[3])
sock = socket.socket(socket.AF_UNIX, socket.SOCK_DGRAM)
sock.bind("\0" + address[1:] if address.startswith("@") else address)
sock.settimeout(0.1)
deadline = time.monotonic() + seconds
start = time.monotonic()
with open(output + ".tmp", "w") as out:
    print("listening", file=out, flush=True)
    while time.monotonic() < deadline:
        try:
            data = sock.recv(4096).decode()
        except socket.timeout:
            continue
        print(f"{time.monotonic() - start:.3f} {data}", file=out, flush=True)
        if data == "STOPPING=1":
            break
import os
os.rename(output + ".tmp", output)
