#!/usr/bin/env python3
"""A stand-in for tev that accepts connections and discards what it receives (for measuring what
`--display-server` costs a render without a tev at hand). Listens on 127.0.0.1 only; each connection
is read to its end and then closed, as tev does. Prints the port, then one line per connection.

Usage: tools/tev_sink.py [PORT]   (default 0: any free port)
"""
import socket
import sys
import threading


def serve(conn, addr):
    total = 0
    with conn:
        while True:
            chunk = conn.recv(1 << 20)
            if not chunk:
                break
            total += len(chunk)
    print(f"connection from port {addr[1]}: {total} bytes", flush=True)


def main(argv):
    if len(argv) > 2:
        print(__doc__, file=sys.stderr)
        return 2
    port = int(argv[1]) if len(argv) == 2 else 0
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        s.bind(("127.0.0.1", port))
        s.listen(8)
        print(f"listening on 127.0.0.1:{s.getsockname()[1]}", flush=True)
        while True:
            conn, addr = s.accept()
            threading.Thread(target=serve, args=(conn, addr), daemon=True).start()


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv))
    except KeyboardInterrupt:
        sys.exit(0)
