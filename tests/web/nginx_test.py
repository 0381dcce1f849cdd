#!/usr/bin/python3
"""docs/deploy.md, run: two `nbar serve` instances behind nginx on 127.0.0.1.

    nginx_test.py NBAR_PROGRAM DOCS_DEPLOY_MD [NGINX_PROGRAM]

The `upstream` and `server` blocks are taken from docs/deploy.md as they are written there (only
the ports change), inside a configuration of this test's own: pid file, logs and temporary files
in a temporary folder, free ports. Exit 0 when it all works, 1 on a failure, 77 (skipped) when
nginx is not installed.
"""
import json
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request

SKIP = 77


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def fail(message):
    print("FAIL: " + message, flush=True)
    sys.exit(1)


def request(port, path, body=None, timeout=60):
    """(status, headers, body bytes) of a GET, or of a POST when body is given."""
    data = None if body is None else (body if isinstance(body, bytes) else json.dumps(body).encode())
    req = urllib.request.Request(f"http://127.0.0.1:{port}{path}", data=data,
                                 headers={"Content-Type": "application/json"} if data is not None else {})
    try:
        with urllib.request.urlopen(req, timeout=timeout) as r:
            return r.status, dict(r.headers), r.read()
    except urllib.error.HTTPError as e:
        return e.code, dict(e.headers), e.read()


def site_from_doc(doc_path):
    """The ```nginx block of docs/deploy.md."""
    text = open(doc_path, encoding="utf-8").read()
    blocks = re.findall(r"```nginx\n(.*?)```", text, re.S)
    if len(blocks) != 1:
        fail(f"{doc_path} should have one nginx block, it has {len(blocks)}")
    return blocks[0]


def start_instance(nbar, folder, name):
    log = open(os.path.join(folder, name + ".log"), "w+")
    process = subprocess.Popen([nbar, "serve", "--port", "0"], stderr=log, stdout=log)
    for _ in range(200):
        log.seek(0)
        found = re.search(r"http://127\.0\.0\.1:(\d+)/", log.read())
        if found:
            return process, int(found.group(1))
        if process.poll() is not None:
            break
        time.sleep(0.05)
    fail(f"nbar serve ({name}) did not start")


def nginx_conf(site, folder, instance_ports, port):
    site = site.replace("127.0.0.1:8081", f"127.0.0.1:{instance_ports[0]}")
    site = site.replace("127.0.0.1:8082", f"127.0.0.1:{instance_ports[1]}")
    site = site.replace("listen 80;", f"listen 127.0.0.1:{port};")
    temp = {k: os.path.join(folder, k) for k in ("body", "proxy", "fastcgi", "uwsgi", "scgi")}
    for path in temp.values():
        os.makedirs(path)
    # As root, nginx's workers would run as "nobody", who cannot write in this folder.
    user = "user root;\n" if os.geteuid() == 0 else ""
    return f"""{user}worker_processes 1;
daemon off;
pid {folder}/nginx.pid;
error_log {folder}/error.log warn;
events {{ worker_connections 256; }}
http {{
    log_format upstreams '$request_method $uri $status $upstream_addr';
    access_log {folder}/access.log upstreams;
    client_body_temp_path {temp['body']};
    proxy_temp_path {temp['proxy']};
    fastcgi_temp_path {temp['fastcgi']};
    uwsgi_temp_path {temp['uwsgi']};
    scgi_temp_path {temp['scgi']};
{site}
}}
"""


def upstreams_used(folder, since_line=0):
    """The instance ports in nginx's access log, from line since_line on (settling the log first)."""
    time.sleep(0.2)
    lines = open(os.path.join(folder, "access.log"), encoding="utf-8").read().splitlines()[since_line:]
    ports = []
    for line in lines:
        # "$upstream_addr" is "127.0.0.1:P", or "127.0.0.1:P, 127.0.0.1:Q" when nginx tried two.
        ports.append([int(p) for p in re.findall(r"127\.0\.0\.1:(\d+)", line)])
    return ports, len(lines) + since_line


def main():
    if len(sys.argv) < 3:
        fail("usage: nginx_test.py NBAR DOCS_DEPLOY_MD [NGINX]")
    nbar, doc = sys.argv[1], sys.argv[2]
    nginx = sys.argv[3] if len(sys.argv) > 3 else (shutil.which("nginx") or
                                                    ("/usr/sbin/nginx" if os.path.exists("/usr/sbin/nginx") else None))
    if not nginx or not os.path.exists(nginx):
        print("SKIP: nginx is not installed (apt-get install nginx; scripts/install-deps.sh installs it)")
        sys.exit(SKIP)
    site = site_from_doc(doc)
    folder = tempfile.mkdtemp(prefix="nbar-nginx-")
    os.chmod(folder, 0o755)
    processes = []
    try:
        a, port_a = start_instance(nbar, folder, "instance-a")
        processes.append(a)
        b, port_b = start_instance(nbar, folder, "instance-b")
        processes.append(b)
        port = free_port()
        conf = os.path.join(folder, "nginx.conf")
        with open(conf, "w") as f:
            f.write(nginx_conf(site, folder, (port_a, port_b), port))
        proxy = subprocess.Popen([nginx, "-p", folder, "-c", conf, "-e", os.path.join(folder, "error.log")],
                                 stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        processes.append(proxy)
        for _ in range(200):
            try:
                if request(port, "/api/health", timeout=2)[0] == 200:
                    break
            except OSError:
                pass
            if proxy.poll() is not None:
                fail("nginx did not start: " + proxy.stderr.read().decode(errors="replace"))
            time.sleep(0.05)
        else:
            fail("nginx does not answer")
        check_both_answer(port, folder, {port_a, port_b})
        check_bodies(port, port_a)
        check_one_down(port, folder, a, port_b)
        print(f"OK: nginx on 127.0.0.1:{port} in front of nbar serve on {port_a} and {port_b}")
    finally:
        for p in reversed(processes):  # nginx first (SIGQUIT: its graceful stop), then the instances
            if p.poll() is None:
                p.send_signal(signal.SIGQUIT if len(p.args) > 1 and p.args[1] == "-p" else signal.SIGTERM)
                try:
                    p.wait(timeout=10)
                except subprocess.TimeoutExpired:
                    p.kill()
                    p.wait()
        shutil.rmtree(folder, ignore_errors=True)


def check_both_answer(port, folder, instance_ports):
    model = request(port, "/api/examples/fourbar-crank-rocker")[2].decode()
    body = {"model": model, "steps": 361}
    direct = request(min(instance_ports), "/api/solve", body)
    if direct[0] != 200:
        fail(f"a solve asked of an instance directly: {direct[0]}")
    for _ in range(12):
        status, headers, answer = request(port, "/api/solve", body)
        if status != 200:
            fail(f"a solve through nginx: {status} {answer[:300]!r}")
        if answer != direct[2]:
            fail("a solve through nginx is not the instance's answer")
        if len(json.loads(answer)["rows"]) != 361:
            fail("a solve through nginx has not 361 rows")
    used, _ = upstreams_used(folder)
    served = {p for ports in used for p in ports}
    if served != instance_ports:
        fail(f"nginx used the instances {sorted(served)}, not both of {sorted(instance_ports)}")


def check_bodies(port, instance_port):
    over_nbar = {"model": "#" * (1536 * 1024)}  # over nbar's 1 MiB, under nginx's 2 MiB
    status, headers, answer = request(port, "/api/check", over_nbar)
    error = json.loads(answer)["error"]
    if status != 413 or error["kind"] != "body_too_large" or error.get("max") != 1 << 20:
        fail(f"a 1.5 MiB body through nginx: {status} {answer[:300]!r}")
    over_nginx = b'{"model": "' + b"#" * (3 << 20) + b'"}'
    try:
        status, headers, answer = request(port, "/api/check", over_nginx)
    except (ConnectionError, urllib.error.URLError) as e:
        fail(f"a 3 MiB body through nginx: the connection broke ({e})")
    if status != 413 or json.loads(answer)["error"]["kind"] != "body_too_large":
        fail(f"a 3 MiB body through nginx: {status} {answer[:300]!r}")


def check_one_down(port, folder, instance, other_port):
    _, seen = upstreams_used(folder)
    instance.send_signal(signal.SIGTERM)
    instance.wait(timeout=10)
    model = request(port, "/api/examples/five-bar")[2].decode()
    for i in range(10):
        status, _, answer = request(port, "/api/check", {"model": model})
        if status != 200 or "dof" not in json.loads(answer):
            fail(f"request {i} with one instance down: {status} {answer[:300]!r}")
    used, _ = upstreams_used(folder, seen)
    # The last instance tried is the one that answered: always the one still up.
    if len(used) < 10 or any(ports[-1] != other_port for ports in used):
        fail(f"with one instance down, nginx's answers came from {used}")


if __name__ == "__main__":
    main()
