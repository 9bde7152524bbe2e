"""The bearing model server: runs the model processes of FMU instances whose master is elsewhere (a Windows tool
with the win64 FMU, or any master with BEARING_FMU_SERVER set).

    bearing serve [--host 127.0.0.1] [--port 7410] [--token-file PATH] [--max-instances N] [--fmu FILE ...]

Each connection is one FMU instance. The handshake comes first, bounded and in this order (bearing_tcp.c):

    frame 1: u32 length, "BRGT", u32 token length, token          (at most HELLO_MAX bytes)
    frame 2: u32 length, u32 protocol, u32 GUID length, GUID      (at most HELLO_MAX bytes)
    reply:   u32 length, u32 code (0: accepted), UTF-8 message

The token is compared in constant time before frame 2 is read. A malformed frame, a wrong token, protocol or
GUID, or no handshake within the handshake timeout closes that connection only, logged with the peer's
address. An accepted connection is handed to a model process of its own (resources/model_process.py --tcp,
started through resources/launch.sh as the native layer starts it locally), which serves the FMI calls over it
until the connection ends, the master stays idle longer than the idle timeout, or this server ends. When the
model process dies the master gets its exit status or signal and the tail of its stderr in a fault frame
(u32 length, u32 kind 1, UTF-8 text). Nothing received is executed or unpickled.
"""
from __future__ import annotations

import argparse
import hashlib
import hmac
import ipaddress
import json
import os
import re
import select
import shutil
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time
import zipfile
from pathlib import Path

DEFAULT_PORT = 7410
HELLO_MAGIC = b"BRGT"
HELLO_MAX = 4096           # bytes of a handshake frame
TOKEN_MAX = 1024
POLLRDHUP = getattr(select, "POLLRDHUP", 0x2000)
FAULT = 1                  # response kind of a fault frame


class Refused(Exception):
    """A handshake the server refuses: the connection is closed with this reason (logged; sent if sendable)."""


def _log(msg: str):
    sys.stderr.write(f"{time.strftime('%Y-%m-%d %H:%M:%S')} bearing serve: {msg}\n")
    sys.stderr.flush()


def is_loopback(host: str) -> bool:
    """Whether every address host resolves to is a loopback address."""
    try:
        infos = socket.getaddrinfo(host, None, type=socket.SOCK_STREAM)
    except socket.gaierror:
        return False
    return bool(infos) and all(ipaddress.ip_address(i[4][0].split("%")[0]).is_loopback for i in infos)


def _recv_exact(conn, n: int) -> bytes:
    buf = bytearray()
    while len(buf) < n:
        b = conn.recv(n - len(buf))
        if not b:
            raise Refused(f"connection ended after {len(buf)} of {n} bytes of a handshake frame")
        buf += b
    return bytes(buf)


def _read_frame(conn, limit: int) -> bytes:
    (n,) = struct.unpack("<I", _recv_exact(conn, 4))
    if n > limit:
        raise Refused(f"handshake frame length {n} bytes; allowed: at most {limit}")
    return _recv_exact(conn, n)


def _fmu_info(unz: Path) -> dict:
    res = unz / "resources"
    cfg = json.loads((res / "model.json").read_text(encoding="utf-8"))
    m = re.search(r"^PROTOCOL = (\d+)", (res / "model_process.py").read_text(encoding="utf-8"), re.M)
    md = (unz / "modelDescription.xml").read_text(encoding="utf-8")
    name = re.search(r'modelName="([^"]*)"', md)
    return {"guid": cfg["guid"], "res": res, "protocol": int(m.group(1)), "name": name.group(1) if name else "?"}


class Server:
    def __init__(self, fmus, host="127.0.0.1", port=DEFAULT_PORT, token=None, max_instances=8,
                 idle_timeout=3600.0, handshake_timeout=10.0):
        self.fmus = {f["guid"]: f for f in fmus}
        self.host, self.port, self.token = host, port, token
        self.max_instances, self.idle, self.hs_timeout = max_instances, idle_timeout, handshake_timeout
        self.lock = threading.Lock()
        self.procs = {}            # pid -> Popen of a running model process
        self.active = 0
        self.stopping = False
        self.sock = None

    # ---- the handshake ----------------------------------------------------------------------------------------
    def _handshake(self, conn) -> dict:
        f1 = _read_frame(conn, HELLO_MAX)
        if len(f1) < 8 or f1[:4] != HELLO_MAGIC:
            raise Refused(f"not a bearing FMU handshake (first bytes {f1[:8]!r})")
        (k,) = struct.unpack_from("<I", f1, 4)
        if k > TOKEN_MAX or 8 + k != len(f1):
            raise Refused(f"malformed token field (length {k} in a frame of {len(f1)} bytes)")
        if self.token is not None:
            # constant time: equal-length digests compared with hmac.compare_digest
            if not hmac.compare_digest(hashlib.sha256(f1[8:]).digest(), hashlib.sha256(self.token).digest()):
                raise Refused("wrong token (BEARING_FMU_TOKEN must hold the server's --token-file contents)")
        f2 = _read_frame(conn, HELLO_MAX)
        if len(f2) < 8:
            raise Refused(f"malformed second handshake frame ({len(f2)} bytes)")
        proto, n = struct.unpack_from("<II", f2)
        if 8 + n != len(f2):
            raise Refused(f"malformed GUID field (length {n} in a frame of {len(f2)} bytes)")
        try:
            guid = f2[8:].decode("ascii")
        except UnicodeDecodeError:
            raise Refused("the GUID is not ASCII") from None
        fmu = self.fmus.get(guid)
        if fmu is None:
            raise Refused(f"GUID {guid!r:.80} is not served here; this server serves "
                          + ", ".join(f"{g} ({f['name']})" for g, f in self.fmus.items())
                          + " (the FMU and the server must come from the same version)")
        if proto != fmu["protocol"]:
            raise Refused(f"protocol {proto} of the FMU's native layer; this server's model process speaks "
                          f"{fmu['protocol']} (the FMU and the server must come from the same version)")
        return fmu

    @staticmethod
    def _reply(conn, code: int, msg: str):
        b = msg.encode("utf-8", "replace")[:HELLO_MAX - 8]
        try:
            conn.sendall(struct.pack("<II", 4 + len(b), code) + b)
        except OSError:
            pass

    # ---- one connection -------------------------------------------------------------------------------------
    def _serve_conn(self, conn, addr):
        peer = f"{addr[0]}:{addr[1]}"
        counted = False
        try:
            conn.settimeout(self.hs_timeout)
            try:
                fmu = self._handshake(conn)
            except socket.timeout:
                raise Refused(f"no complete handshake within {self.hs_timeout:g} s (half-open or silent client)")
            except OSError as e:
                raise Refused(f"connection error during the handshake: {e}")
            with self.lock:
                if self.stopping:
                    raise Refused("the server is stopping")
                if self.active >= self.max_instances:
                    raise Refused(f"the server already runs {self.active} instances, its limit (--max-instances "
                                  f"{self.max_instances})")
                self.active += 1
                counted = True
            self._run_instance(conn, peer, fmu)
        except Refused as e:
            _log(f"{peer}: connection closed: {e}")
            self._reply(conn, 1, f"bearing model server: {e}")
        finally:
            if counted:
                with self.lock:
                    self.active -= 1
            try:
                conn.shutdown(socket.SHUT_RDWR)
            except OSError:
                pass
            conn.close()

    def _run_instance(self, conn, peer, fmu):
        res = fmu["res"]
        fd = conn.fileno()
        errf = tempfile.TemporaryFile()
        try:
            proc = subprocess.Popen(["/bin/sh", str(res / "launch.sh"), str(res / "model_process.py"), str(res),
                                     "--tcp", str(fd), str(os.getpid()), repr(float(self.idle))],
                                    pass_fds=(fd,), stdin=subprocess.DEVNULL, stdout=errf, stderr=errf)
        except OSError as e:
            errf.close()
            raise Refused(f"cannot start a model process: {e}")
        with self.lock:
            self.procs[proc.pid] = proc
        self._reply(conn, 0, "accepted")
        _log(f"{peer}: instance of {fmu['name']} {fmu['guid']}: model process {proc.pid}")
        poll = select.poll()
        poll.register(fd, POLLRDHUP | select.POLLHUP | select.POLLERR)
        peer_closed = False
        try:
            while proc.poll() is None:
                if poll.poll(200):
                    peer_closed = True    # the master closed (or the network failed): the model process ends
                    try:
                        proc.wait(5.0)
                    except subprocess.TimeoutExpired:
                        proc.kill()
                        proc.wait()
                    break
            rc = proc.returncode
            if rc == 0:
                why = "the model process ended normally"
            elif rc < 0:
                try:
                    why = f"the model process was killed by signal {-rc} ({signal.Signals(-rc).name})"
                except ValueError:
                    why = f"the model process was killed by signal {-rc}"
            else:
                why = f"the model process exited with status {rc}"
            tail = ""
            errf.seek(0, 2)
            size = errf.tell()
            errf.seek(max(0, size - 3072))
            tail = errf.read().decode("utf-8", "replace").strip()
            if size > 3072 and "\n" in tail:
                tail = tail.split("\n", 1)[1]
            if rc != 0 and not peer_closed:
                text = why + (f". Last output of the model process:\n{tail}" if tail else "")
                b = text.encode("utf-8", "replace")[:HELLO_MAX * 4]
                try:
                    conn.sendall(struct.pack("<II", 4 + len(b), FAULT) + b)
                except OSError:
                    pass
            _log(f"{peer}: instance ended ({'master closed the connection; ' if peer_closed else ''}{why})"
                 + (f"; its stderr: {tail[-500:]}" if rc != -9 and tail else ""))
        finally:
            if proc.poll() is None:
                proc.kill()
                proc.wait()
            with self.lock:
                self.procs.pop(proc.pid, None)
            errf.close()

    # ---- the server -------------------------------------------------------------------------------------------
    def bind(self):
        infos = socket.getaddrinfo(self.host, self.port, type=socket.SOCK_STREAM)
        fam, _, _, _, sa = infos[0]
        s = socket.socket(fam, socket.SOCK_STREAM)
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        s.bind(sa)
        s.listen(64)
        self.sock = s
        self.port = s.getsockname()[1]
        return s

    def serve_forever(self):
        if self.sock is None:
            self.bind()
        _log(f"listening on {self.host}:{self.port} ({'token required' if self.token else 'no token'}; at most "
             f"{self.max_instances} instances; idle timeout {self.idle:g} s); serving "
             + ", ".join(f"{f['name']} {g}" for g, f in self.fmus.items()))
        sys.stdout.write(f"bearing serve: listening on {self.host}:{self.port}\n")
        sys.stdout.flush()
        try:
            while True:
                conn, addr = self.sock.accept()
                conn.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
                conn.setsockopt(socket.SOL_SOCKET, socket.SO_KEEPALIVE, 1)
                for opt, v in (("TCP_KEEPIDLE", 30), ("TCP_KEEPINTVL", 10), ("TCP_KEEPCNT", 3)):
                    if hasattr(socket, opt):
                        conn.setsockopt(socket.IPPROTO_TCP, getattr(socket, opt), v)
                threading.Thread(target=self._serve_conn, args=(conn, addr), daemon=True).start()
        except KeyboardInterrupt:
            pass
        finally:
            self.stop()
        return 0

    def stop(self):
        """Stops accepting and ends every model process this server started."""
        with self.lock:
            self.stopping = True
            procs = list(self.procs.values())
        if self.sock is not None:
            self.sock.close()
        for p in procs:
            try:
                p.kill()
            except OSError:
                pass
        for p in procs:
            try:
                p.wait(5)
            except subprocess.TimeoutExpired:
                pass
        _log(f"stopped; {len(procs)} model process(es) ended")


def _unpack(fmu: Path, into: Path) -> Path:
    with zipfile.ZipFile(fmu) as z:
        z.extractall(into)
    return into


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="bearing serve", description=__doc__.splitlines()[0])
    add_arguments(ap)
    return run(ap.parse_args(argv))


def add_arguments(ap):
    ap.add_argument("--host", default="127.0.0.1",
                    help="address to listen on (default 127.0.0.1: this machine only; a non-loopback address "
                         "requires --token-file)")
    ap.add_argument("--port", type=int, default=DEFAULT_PORT, help=f"TCP port (default {DEFAULT_PORT}; 0: any free)")
    ap.add_argument("--token-file", default=None, metavar="PATH",
                    help="file holding the token a master must send (its BEARING_FMU_TOKEN); required off loopback")
    ap.add_argument("--max-instances", type=int, default=8, metavar="N",
                    help="FMU instances served at once (default 8); more are refused at the handshake")
    ap.add_argument("--fmu", action="append", default=[], metavar="FILE",
                    help="serve this FMU (repeatable; default: the bearing FMU of this installation, built once "
                         "into the cache)")
    ap.add_argument("--idle-timeout", type=float, default=3600.0, metavar="SECONDS",
                    help="a connection with no request for this long is closed and its model process ends "
                         "(default 3600)")
    ap.add_argument("--handshake-timeout", type=float, default=10.0, metavar="SECONDS",
                    help="a client must complete its handshake within this (default 10)")


class UsageError(Exception):
    pass


def check_args(a):
    if not 0 <= a.port <= 65535:
        raise UsageError(f"--port = {a.port} is invalid; allowed: 0..65535")
    if not 1 <= a.max_instances <= 1024:
        raise UsageError(f"--max-instances = {a.max_instances} is invalid; allowed: 1..1024")
    if not 1.0 <= a.idle_timeout <= 1e6:
        raise UsageError(f"--idle-timeout = {a.idle_timeout} is invalid; allowed: 1..1e6 s")
    if not 0.1 <= a.handshake_timeout <= 600:
        raise UsageError(f"--handshake-timeout = {a.handshake_timeout} is invalid; allowed: 0.1..600 s")
    token = None
    if a.token_file is not None:
        p = Path(a.token_file)
        if not p.is_file():
            raise UsageError(f"--token-file = {a.token_file!r} is not a file")
        token = p.read_bytes().strip()
        if not 16 <= len(token) <= TOKEN_MAX:
            raise UsageError(f"--token-file {a.token_file!r} holds a token of {len(token)} bytes; allowed: "
                             f"16..{TOKEN_MAX} bytes (e.g. python -c \"import secrets; print(secrets.token_hex(32))\")")
    if not is_loopback(a.host) and token is None:
        raise UsageError(f"--host = {a.host!r} is not a loopback address: listening there requires --token-file "
                         "(the token masters send as BEARING_FMU_TOKEN)")
    for f in a.fmu:
        if not Path(f).is_file():
            raise UsageError(f"--fmu = {f!r} is not a file")
    return token


def run(a) -> int:
    try:
        token = check_args(a)
    except UsageError as e:
        sys.stderr.write(f"bearing serve: error: {e}\n")
        return 2
    tmp = Path(tempfile.mkdtemp(prefix="bearing_serve_"))
    try:
        fmus = []
        files = [Path(f) for f in a.fmu]
        if not files:
            from .fmu_build import build
            files = [build(tmp / "dist")]
        for k, f in enumerate(files):
            fmus.append(_fmu_info(_unpack(f, tmp / f"fmu{k}")))
        srv = Server(fmus, a.host, a.port, token, a.max_instances, a.idle_timeout, a.handshake_timeout)
        try:
            srv.bind()
        except OSError as e:
            sys.stderr.write(f"bearing serve: error: cannot listen on {a.host}:{a.port}: {e}\n")
            return 2
        signal.signal(signal.SIGTERM, lambda *_: (_ for _ in ()).throw(KeyboardInterrupt()))
        return srv.serve_forever()
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
