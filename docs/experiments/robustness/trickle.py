# Usage: python3 trickle.py FAIR TIMEOUT_S: 16 connections trickle a byte a second, then one
# normal GET /api/methods; prints its status line and time, or that none came.
import socket, subprocess, sys, time, threading
fair = sys.argv[1]
p = subprocess.Popen([fair, "serve", "--port", "0", "--quiet"], stdout=subprocess.PIPE, text=True)
addr = p.stdout.readline().strip().removeprefix("fair serve: http://").rstrip("/")
host, port = addr.rsplit(":", 1)
slow = []
for _ in range(16):
    s = socket.create_connection((host, int(port)))
    s.sendall(f"GET /api/methods HTTP/1.1\r\nHost: {addr}\r\nX-Slow: ".encode())
    slow.append(s)
stop = False
def trickle():
    while not stop:
        for s in slow:
            try: s.sendall(b"a")
            except OSError: pass
        time.sleep(1)
threading.Thread(target=trickle, daemon=True).start()
time.sleep(0.5)
t = time.time()
c = socket.create_connection((host, int(port)))
c.settimeout(float(sys.argv[2]))
c.sendall(f"GET /api/methods HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n".encode())
try:
    first = c.recv(64).split(b"\r\n")[0].decode()
    print(f"normal request: {first!r} after {time.time()-t:.2f} s")
except socket.timeout:
    print(f"normal request: no answer after {time.time()-t:.0f} s")
stop = True
p.kill()
