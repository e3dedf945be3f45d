#!/usr/bin/env bash
# gjkdem view: serves the page, three.js and the run folder on 127.0.0.1,
# uncompressed, and nothing else (not the rest of node_modules, nothing above
# the run folder);
# refuses a folder that is not a run, a busy port, and a page not built.
set -euo pipefail
gjkdem="$1"
run="$2"    # a run folder (the browser tests' fixture)
web="$3"    # the page's folder (web/)
[ -f "$web/node_modules/three/build/three.module.js" ] || { echo "SKIP: web/node_modules not installed (npm ci in web/)"; exit 77; }
work="$(mktemp -d)"
pid=""
trap '[ -n "$pid" ] && kill "$pid" 2>/dev/null; rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$gjkdem" view "$run" --port 0 --web "$web" > "$work/said.txt" &
pid=$!
for _ in $(seq 1 100); do grep -q "http://127.0.0.1:" "$work/said.txt" && break; sleep 0.1; done
url="$(grep -o 'http://127.0.0.1:[0-9]*/' "$work/said.txt")" || fail "no address printed: $(cat "$work/said.txt")"
port="${url#http://127.0.0.1:}"; port="${port%/}"

/usr/bin/python3 - "$url" "$run" <<'PY' || fail "the routes"
import sys, urllib.request, urllib.error, http.client
url, run = sys.argv[1], sys.argv[2]
def get(path):
    try:
        with urllib.request.urlopen(url + path.lstrip("/")) as r:
            return r.status, r.read(), r.headers
    except urllib.error.HTTPError as e:
        return e.code, b"", e.headers
status, body, _ = get("/")
assert status == 200 and b"<html" in body.lower(), ("page", status)
status, body, _ = get("/vendor/three/three.module.js")
assert status == 200 and len(body) > 100000, ("three.js", status)
status, body, headers = get("/run/view/index.csv")
assert status == 200 and body == open(run + "/view/index.csv", "rb").read(), ("index", status)
assert headers.get("Cache-Control") == "no-store", "a live run's files must not be cached"
status, body, _ = get("/run/view/frame_000000.bin")
assert status == 200 and body[:8] == b"GJKFRAME", ("frame", status)
assert get("/node_modules/three/package.json")[0] == 404, "node_modules is not served"
# Not compressed, though the browser accepts it (httplib's Brotli took 1.9 s for three.js).
req = urllib.request.Request(url + "vendor/three/three.module.js", headers={"Accept-Encoding": "gzip, deflate, br"})
with urllib.request.urlopen(req) as r:
    assert r.headers.get("Content-Encoding") is None, r.headers.get("Content-Encoding")
assert get("/run/nothing_here.txt")[0] == 404
for sneaky in ("/./node_modules/three/package.json", "//node_modules/three/package.json",
               "/vendor/../node_modules/three/package.json"):
    c = http.client.HTTPConnection(url.split("//")[1].rstrip("/"))
    c.request("GET", sneaky)
    assert c.getresponse().status in (400, 404), sneaky
# Another Host (a rebound name) is refused; localhost is this server too.
port = url.split(":")[2].rstrip("/")
for host, expected in (("evil.example:" + port, 403), ("localhost:" + port, 200)):
    c = http.client.HTTPConnection(url.split("//")[1].rstrip("/"))
    c.request("GET", "/run/view/index.csv", headers={"Host": host})
    assert c.getresponse().status == expected, host
# A path climbing out of the run folder (sent raw: urllib would clean it up).
c = http.client.HTTPConnection(url.split("//")[1].rstrip("/"))
c.request("GET", "/run/../../../etc/passwd")
r = c.getresponse()
assert r.status in (400, 404) and b"root:" not in r.read(), ("traversal", r.status)
PY

# Symbolic links inside a run folder are not followed: a link to a file or a
# folder outside it (/etc/passwd, /) is not served, the folder's own files are.
cp -r "$run" "$work/linked"
ln -s /etc/passwd "$work/linked/passwd"
ln -s / "$work/linked/root"
ln -s "$work/linked/view" "$work/linked/view_again"
"$gjkdem" view "$work/linked" --port 0 --web "$web" > "$work/said2.txt" &
pid2=$!
for _ in $(seq 1 100); do grep -q "http://127.0.0.1:" "$work/said2.txt" && break; sleep 0.1; done
url2="$(grep -o 'http://127.0.0.1:[0-9]*/' "$work/said2.txt")" || fail "no address printed: $(cat "$work/said2.txt")"
/usr/bin/python3 - "$url2" <<'PY' || { kill "$pid2"; fail "symbolic links"; }
import sys, urllib.request, urllib.error
url = sys.argv[1]
def status(path):
    try:
        with urllib.request.urlopen(url + path.lstrip("/")) as r:
            return r.status
    except urllib.error.HTTPError as e:
        return e.code
assert status("/run/view/index.csv") == 200, "the run's own file"
for linked in ("/run/passwd", "/run/root/etc/passwd", "/run/view_again/index.csv", "/runpasswd",
               "/runroot/etc/passwd"):
    assert status(linked) == 404, linked
# Generated requests (seeded): paths of dots, encodings, links and junk, odd
# methods and hosts. Each gets an answer, nothing outside the run folder is
# served, and the server still serves the run afterwards.
import http.client, random
rng = random.Random(5)
host = url.split("//")[1].rstrip("/")
parts = ["run", "view", "..", ".", "%2e%2e", "%2E%2e%2f", "passwd", "root", "etc", "index.csv", "%00", "a" * 300,
         "view_again", "frame_000000.bin", "node_modules", "vendor", "three", "%ff", "~", ";", "?x=1", "#f"]
for k in range(300):
    path = "/" + "/".join(rng.choice(parts) for _ in range(rng.randrange(1, 7)))
    method = rng.choice(["GET", "GET", "GET", "HEAD", "POST", "PUT", "DELETE", "OPTIONS"])
    headers = {"Host": rng.choice([host, host, "evil.example", "", "localhost:" + host.split(":")[1]])}
    c = http.client.HTTPConnection(host, timeout=10)
    try:
        c.request(method, path, headers=headers)
        r = c.getresponse()
        body = r.read()
    finally:
        c.close()
    assert r.status in (200, 204, 400, 403, 404, 405, 414, 501), (method, path, r.status)
    assert b"root:" not in body, (method, path)
assert status("/run/view/index.csv") == 200, "the server still serves the run"
print("view: answered", k + 1, "generated requests")
PY
kill "$pid2"

# Refusals: exit 2 with a message.
refused() {  # refused EXPECTED ARGS...
  local expected="$1"; shift
  set +e
  "$gjkdem" view "$@" > /dev/null 2> "$work/err.txt"
  local rc=$?
  set -e
  [ "$rc" -eq 2 ] && grep -q "$expected" "$work/err.txt" || fail "view $* should be refused with \"$expected\" (rc $rc): $(cat "$work/err.txt")"
}
mkdir "$work/empty"
refused "holds no view frames" "$work/empty" --port 0 --web "$web"
refused "cannot listen on 127.0.0.1:$port" "$run" --port "$port" --web "$web"
refused "the viewer's page is not built" "$run" --port 0 --web "$work/empty"
echo "view: ok"
