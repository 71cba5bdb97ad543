#!/usr/bin/env python3
"""A TCP relay that records what passes: the "wire" of the security test.

    tcp_relay.py LISTEN_PORT TARGET_PORT CAPTURE_FILE

Accepts connections on 127.0.0.1:LISTEN_PORT, forwards each to
127.0.0.1:TARGET_PORT, and appends every byte it forwards, in both
directions, to CAPTURE_FILE. Prints "ready" once listening. Runs until
killed. Standard library only.
"""

import socket
import sys
import threading

lock = threading.Lock()


def pump(source, sink, capture):
    try:
        while True:
            data = source.recv(65536)
            if not data:
                break
            with lock:
                capture.write(data)
                capture.flush()
            sink.sendall(data)
    except OSError:
        pass
    finally:
        for s in (source, sink):
            try:
                s.shutdown(socket.SHUT_RDWR)
            except OSError:
                pass


def main():
    listen_port, target_port, path = int(sys.argv[1]), int(sys.argv[2]), sys.argv[3]
    capture = open(path, "ab")
    server = socket.socket()
    server.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    server.bind(("127.0.0.1", listen_port))
    server.listen(16)
    print("ready", flush=True)
    while True:
        client, _ = server.accept()
        try:
            upstream = socket.create_connection(("127.0.0.1", target_port))
        except OSError:
            client.close()
            continue
        for a, b in ((client, upstream), (upstream, client)):
            threading.Thread(target=pump, args=(a, b, capture), daemon=True).start()


if __name__ == "__main__":
    main()
