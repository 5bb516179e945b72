"""Offline check of deploy/k8s (tests/scripts/k8s_manifests.sh).

1. Schema: every document is decoded strictly against the Kubernetes API
   models of Debian's python3-kubernetes (unknown fields, wrong types and
   missing required fields are errors) -- an independent description of the
   API, not ours.
2. Wiring: the Service selects the coordinator's pods and targets its port,
   workers dial that Service, both read the token from one Secret and share
   the ReadWriteMany store claim, probes run `wavebake health`, the workers'
   grace period outlasts a task.
3. Rehearsal: the containers' own args and probe commands run here, with
   only the mount paths and the Service address mapped to this machine: the
   coordinator serves, its probes pass, a worker registers, bakes a job and
   drains at SIGTERM.

usage: k8s_check.py WAVEBAKE DEPLOY_K8S_DIR TMP
"""
import os
import re
import signal
import subprocess
import sys
import time

import kubernetes.client as k8s
import yaml

WB, K8S, TMP = sys.argv[1], sys.argv[2], sys.argv[3]
MODELS = {
    ("v1", "Namespace"): "V1Namespace",
    ("v1", "Service"): "V1Service",
    ("v1", "PersistentVolumeClaim"): "V1PersistentVolumeClaim",
    ("apps/v1", "StatefulSet"): "V1StatefulSet",
    ("apps/v1", "Deployment"): "V1Deployment",
}
PRIMITIVES = {"str": str, "int": int, "bool": bool, "float": (int, float)}


def fail(msg):
    print("FAIL: " + msg, file=sys.stderr)
    sys.exit(1)


def check(value, type_name, path):
    """Strict structural check of `value` against a python3-kubernetes type."""
    if type_name.startswith("list["):
        if not isinstance(value, list):
            fail(f"{path}: expected a list")
        for i, v in enumerate(value):
            check(v, type_name[5:-1], f"{path}[{i}]")
    elif type_name.startswith("dict("):
        if not isinstance(value, dict):
            fail(f"{path}: expected a map")
        inner = type_name[5:-1].split(", ", 1)[1]
        for key, v in value.items():
            check(v, inner, f"{path}.{key}")
    elif type_name in PRIMITIVES:
        if not isinstance(value, PRIMITIVES[type_name]) or (
            type_name != "bool" and isinstance(value, bool)
        ):
            fail(f"{path}: expected {type_name}, got {value!r}")
    elif type_name == "object":
        pass  # IntOrString / Quantity: either form
    else:
        model = getattr(k8s, type_name)
        if not isinstance(value, dict):
            fail(f"{path}: expected a {type_name} object")
        by_json = {j: a for a, j in model.attribute_map.items()}
        for key, v in value.items():
            if key not in by_json:
                fail(f"{path}: unknown field '{key}' in {type_name}")
            check(v, model.openapi_types[by_json[key]], f"{path}.{key}")


def load():
    with open(os.path.join(K8S, "kustomization.yaml")) as f:
        kust = yaml.safe_load(f)
    listed = set(kust["resources"])
    present = {n for n in os.listdir(K8S) if n.endswith(".yaml") and n != "kustomization.yaml"}
    if listed != present:
        fail(f"kustomization.yaml lists {sorted(listed)}, the directory has {sorted(present)}")
    docs = []
    for name in kust["resources"]:
        with open(os.path.join(K8S, name)) as f:
            for doc in yaml.safe_load_all(f):
                key = (doc.get("apiVersion"), doc.get("kind"))
                if key not in MODELS:
                    fail(f"{name}: no model for {key}")
                check(doc, MODELS[key], f"{name}:{doc['kind']}")
                # Required fields: the models' own validation.
                try:
                    k8s.ApiClient()._ApiClient__deserialize(doc, MODELS[key])
                except ValueError as e:
                    fail(f"{name}:{doc['kind']}: {e}")
                docs.append(doc)
    return docs


def one(docs, kind):
    found = [d for d in docs if d["kind"] == kind]
    if len(found) != 1:
        fail(f"expected one {kind}, found {len(found)}")
    return found[0]


def flags(container):
    out = {}
    for a in container.get("args", []):
        m = re.fullmatch(r"--([a-z-]+)=(.*)", a)
        if m:
            out[m.group(1)] = m.group(2)
    return out


def mounts(pod, container):
    volumes = {v["name"]: v for v in pod["volumes"]} if "volumes" in pod else {}
    return {m["mountPath"]: volumes.get(m["name"], {"name": m["name"]}) for m in container["volumeMounts"]}


def wiring(docs):
    svc, sts, dep = one(docs, "Service"), one(docs, "StatefulSet"), one(docs, "Deployment")
    pvc = one(docs, "PersistentVolumeClaim")
    cpod, wpod = sts["spec"]["template"], dep["spec"]["template"]
    coord, worker = cpod["spec"]["containers"][0], wpod["spec"]["containers"][0]
    labels = cpod["metadata"]["labels"]
    if any(labels.get(k) != v for k, v in svc["spec"]["selector"].items()):
        fail("the Service's selector does not select the coordinator's pods")
    if sts["spec"]["selector"]["matchLabels"] != labels:
        fail("the StatefulSet's selector is not its pods' labels")
    if sts["spec"]["serviceName"] != svc["metadata"]["name"]:
        fail("the StatefulSet's serviceName is not the Service")
    port = svc["spec"]["ports"][0]
    cport = {p["name"]: p["containerPort"] for p in coord["ports"]}
    if cport.get(port["targetPort"]) != int(flags(coord)["listen"].rsplit(":", 1)[1]):
        fail("the Service's targetPort is not the port the coordinator listens on")
    if flags(worker)["coordinator"] != f"{svc['metadata']['name']}:{port['port']}":
        fail(f"workers dial {flags(worker)['coordinator']}, not the Service")
    cm, wm = mounts(cpod["spec"], coord), mounts(wpod["spec"], worker)
    for f, m in ((flags(coord), cm), (flags(worker), wm)):
        store = m[f["store-root"]]
        if store.get("persistentVolumeClaim", {}).get("claimName") != pvc["metadata"]["name"]:
            fail("--store-root is not on the shared store claim")
        token_dir = os.path.dirname(f["token-file"])
        if "secret" not in m.get(token_dir, {}):
            fail("--token-file is not on a Secret volume")
    if cm[os.path.dirname(flags(coord)["token-file"])]["secret"]["secretName"] != \
            wm[os.path.dirname(flags(worker)["token-file"])]["secret"]["secretName"]:
        fail("coordinator and workers read the token from different Secrets")
    if "ReadWriteMany" not in pvc["spec"]["accessModes"]:
        fail("the store claim is not ReadWriteMany")
    claims = {t["metadata"]["name"] for t in sts["spec"]["volumeClaimTemplates"]}
    if cm.get(flags(coord)["data"], {}).get("name") not in claims:
        fail("--data is not on the StatefulSet's own claim")
    for c, probes in ((coord, ("readinessProbe", "livenessProbe")), (worker, ("readinessProbe",))):
        for p in probes:
            cmd = c.get(p, {}).get("exec", {}).get("command", [])
            if cmd[:2] != ["wavebake", "health"]:
                fail(f"{c['name']}.{p} is not `wavebake health`: {cmd}")
    lease = float(flags(coord)["lease-seconds"])
    grace = wpod["spec"]["terminationGracePeriodSeconds"]
    # A task runs minutes at large N (a 32×32 tile at N = 256); drain needs it to finish.
    if grace < 600 or grace <= lease:
        fail(f"worker grace period {grace} s is shorter than a long task (>= 600 s)")
    return coord, worker, cm, wm


def expand(arg, env):
    return re.sub(r"\$\(([A-Z_]+)\)", lambda m: env[m.group(1)], arg)


def rehearse(coord, worker, cm, wm):
    root = {path: os.path.join(TMP, "mnt" + path.replace("/", "_")) for path in {**cm, **wm}}
    for d in root.values():
        os.makedirs(d, exist_ok=True)
    tokdir = root[os.path.dirname(flags(coord)["token-file"])]
    with open(os.path.join(tokdir, "token"), "w") as f:
        f.write("k8s-rehearsal-token\n")
    if root[os.path.dirname(flags(worker)["token-file"])] != tokdir:
        os.symlink(os.path.join(tokdir, "token"),
                   os.path.join(root[os.path.dirname(flags(worker)["token-file"])], "token"))

    def mapped(args, addr=None):
        out = []
        for a in args:
            for path in sorted(root, key=len, reverse=True):
                a = re.sub(rf"=({re.escape(path)})(/|$)", lambda m: "=" + root[path] + m.group(2), a)
            if addr and a.startswith("--coordinator="):
                a = "--coordinator=" + addr
            out.append(a)
        return out

    procs = []
    try:
        args = [a for a in mapped(coord["args"]) if not a.startswith("--listen=")]
        addr_file = os.path.join(TMP, "coordinator.addr")
        clog = open(os.path.join(TMP, "k8s-coordinator.log"), "w")
        procs.append(subprocess.Popen([WB] + args + ["--listen=127.0.0.1:0", f"--address-file={addr_file}"],
                                      stdout=clog, stderr=subprocess.STDOUT))
        deadline = time.time() + 20
        while not (os.path.exists(addr_file) and open(addr_file).read().strip()):
            if time.time() > deadline or procs[0].poll() is not None:
                fail("the coordinator's container args do not start a coordinator")
            time.sleep(0.1)
        addr = open(addr_file).read().strip()
        for p in ("readinessProbe", "livenessProbe"):
            cmd = mapped(coord[p]["exec"]["command"], addr)
            r = subprocess.run([WB] + cmd[1:], capture_output=True, text=True, timeout=30)
            if r.returncode != 0:
                fail(f"coordinator {p} failed: {r.stderr.strip()}")
        env = {"WB_THREADS": "2", "POD_NAME": "wavebake-worker-rehearsal"}
        wlog_path = os.path.join(TMP, "k8s-worker.log")
        wlog = open(wlog_path, "w")
        wargs = [expand(a, env) for a in mapped(worker["args"], addr)]
        procs.append(subprocess.Popen([WB] + wargs, stdout=wlog, stderr=subprocess.STDOUT))
        cmd = mapped(worker["readinessProbe"]["exec"]["command"], addr)
        if subprocess.run([WB] + cmd[1:], capture_output=True, timeout=30).returncode != 0:
            fail("worker readinessProbe failed")
        token = ["--coordinator", addr, "--token-file", os.path.join(tokdir, "token")]
        job = subprocess.run([WB, "submit", "builtin:furnace", "--light-res", "8", "--layout",
                              "camera:16x16", "--wait"] + token,
                             capture_output=True, text=True, timeout=120)
        if job.returncode != 0:
            fail(f"a job on the rehearsed deployment did not finish: {job.stderr[-300:]}")
        procs[1].send_signal(signal.SIGTERM)  # what the kubelet sends first
        if procs[1].wait(timeout=30) != 0:
            fail("the worker did not drain and exit 0 at SIGTERM")
        if "registered as \"wavebake-worker-rehearsal\" with 2 thread(s)" not in open(wlog_path).read():
            fail("the worker did not take its name and threads from the pod's env")
    finally:
        for p in procs:
            if p.poll() is None:
                p.kill()
                p.wait()


docs = load()
rehearse(*wiring(docs))
print(f"PASS: {len(docs)} manifests valid against python3-kubernetes' API models; wiring "
      "checked; coordinator, probes and worker rehearsed from their own args")
