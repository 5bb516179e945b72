"""Offline check of deploy/k8s (tests/scripts/k8s_manifests.sh): a policy
test, since there is no cluster here.

1. Schema: every document is decoded strictly against the Kubernetes API
   models of Debian's python3-kubernetes (unknown fields, wrong types and
   missing required fields are errors) -- an independent description of the
   API, not ours. Fields newer than those models (22.6: the grpc probe) are
   checked against the API reference's shape, written out below.
2. Wiring: the Service selects the coordinator's pods and targets its ports,
   workers dial that Service over TLS, both read the token from one Secret
   and the TLS material from another, and share the ReadWriteMany store claim.
3. Policy, item by item: the coordinator serves --http on a Service port
   with Prometheus scrape annotations (and the ServiceMonitor example
   matches the Service); images named through kustomize `images:` with a
   versioned tag (the project's version); the "restricted" Pod Security
   Standard (runAsNonRoot, no privilege escalation, capabilities drop ALL,
   seccomp RuntimeDefault, only its allowed volume types, no host
   namespaces or ports) plus a read-only root filesystem with every path
   the program writes on a writable emptyDir or claim; requests and limits
   on every container; a PodDisruptionBudget for the workers; NetworkPolicy
   selecting every pod; built-in grpc probes on the coordinator's plain
   health port; grace periods within the cluster autoscaler's 600 s; a
   multi-stage Dockerfile whose runtime stage installs only runtime
   libraries -- checked against `ldd` of the binary under test and apt's
   dependency closure -- and whose list the README repeats.
4. Rehearsal: the containers' own args and probes run here, with only the
   mount paths, listen ports and the Service address mapped to this machine
   and a test certificate in the TLS Secret's place: the coordinator serves
   gRPC over TLS, the kubelet's grpc probe (plain text) passes on the health
   port, /metrics answers over HTTPS with the token as the scrape
   annotations say, a worker registers over TLS, bakes a job and drains at
   SIGTERM.

usage: k8s_check.py WAVEBAKE DEPLOY_K8S_DIR TMP [SOURCE_DIR]
"""
import os
import re
import signal
import socket
import ssl
import urllib.request
import subprocess
import sys
import time

import kubernetes.client as k8s
import yaml

WB, K8S, TMP = sys.argv[1], sys.argv[2], sys.argv[3]
SRC = sys.argv[4] if len(sys.argv) > 4 else os.path.dirname(os.path.dirname(K8S))
MODELS = {
    ("v1", "Namespace"): "V1Namespace",
    ("v1", "Service"): "V1Service",
    ("v1", "PersistentVolumeClaim"): "V1PersistentVolumeClaim",
    ("apps/v1", "StatefulSet"): "V1StatefulSet",
    ("apps/v1", "Deployment"): "V1Deployment",
    ("policy/v1", "PodDisruptionBudget"): "V1PodDisruptionBudget",
    ("networking.k8s.io/v1", "NetworkPolicy"): "V1NetworkPolicy",
}
# Fields the API gained after python3-kubernetes 22.6's models, from the API
# reference (Probe.grpc: GRPCAction{port int32 required, service string};
# beta in 1.24, GA in 1.27).
NEWER_FIELDS = {("V1Probe", "grpc"): {"port": int, "service": str}}
NEWER_REQUIRED = {("V1Probe", "grpc"): {"port"}}
PRIMITIVES = {"str": str, "int": int, "bool": bool, "float": (int, float)}
# The health service --health-listen keeps SERVING while the process serves
# (kLivenessService, coordinator/service/coordinator.h).
LIVENESS_SERVICE = "liveness"


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
            if (type_name, key) in NEWER_FIELDS:
                shape = NEWER_FIELDS[(type_name, key)]
                if not isinstance(v, dict) or set(v) - set(shape) or \
                        NEWER_REQUIRED[(type_name, key)] - set(v) or \
                        any(not isinstance(v[k], shape[k]) for k in v):
                    fail(f"{path}.{key}: not a {type_name}.{key} of shape {shape}")
                continue
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


def selects(selector, labels):
    return all(labels.get(k) == v for k, v in selector.items())


def wiring(docs):
    svc, sts, dep = one(docs, "Service"), one(docs, "StatefulSet"), one(docs, "Deployment")
    pvc = one(docs, "PersistentVolumeClaim")
    cpod, wpod = sts["spec"]["template"], dep["spec"]["template"]
    coord, worker = cpod["spec"]["containers"][0], wpod["spec"]["containers"][0]
    labels = cpod["metadata"]["labels"]
    if not selects(svc["spec"]["selector"], labels) or selects(svc["spec"]["selector"],
                                                              wpod["metadata"]["labels"]):
        fail("the Service's selector does not select the coordinator's pods alone")
    if sts["spec"]["selector"]["matchLabels"] != labels:
        fail("the StatefulSet's selector is not its pods' labels")
    if sts["spec"]["serviceName"] != svc["metadata"]["name"]:
        fail("the StatefulSet's serviceName is not the Service")
    sports = {p["name"]: p for p in svc["spec"]["ports"]}
    cport = {p["name"]: p["containerPort"] for p in coord["ports"]}
    cf, wf = flags(coord), flags(worker)
    for name, flag in (("grpc", "listen"), ("http", "http")):
        if name not in sports:
            fail(f"the Service has no port named {name}")
        if flag not in cf:
            fail(f"the coordinator runs without --{flag}")
        if cport.get(sports[name]["targetPort"]) != int(cf[flag].rsplit(":", 1)[1]):
            fail(f"the Service's {name} targetPort is not the port of the coordinator's --{flag}")
    if wf["coordinator"] != f"{svc['metadata']['name']}:{sports['grpc']['port']}":
        fail(f"workers dial {wf['coordinator']}, not the Service")
    cm, wm = mounts(cpod["spec"], coord), mounts(wpod["spec"], worker)
    for f, m in ((cf, cm), (wf, wm)):
        store = m[f["store-root"]]
        if store.get("persistentVolumeClaim", {}).get("claimName") != pvc["metadata"]["name"]:
            fail("--store-root is not on the shared store claim")
        token_dir = os.path.dirname(f["token-file"])
        if "secret" not in m.get(token_dir, {}):
            fail("--token-file is not on a Secret volume")
    secret = lambda m, f: m[os.path.dirname(f)]["secret"]["secretName"]
    if secret(cm, cf["token-file"]) != secret(wm, wf["token-file"]):
        fail("coordinator and workers read the token from different Secrets")
    # TLS between pods: the coordinator's certificate and key and the
    # workers' CA from one Secret (not the token's).
    for f, m, keys in ((cf, cm, ("tls-cert", "tls-key")), (wf, wm, ("tls-ca",))):
        for k in keys:
            if k not in f or "secret" not in m.get(os.path.dirname(f[k]), {}):
                fail(f"--{k} is not given from a Secret volume")
    tls_secret = secret(cm, cf["tls-cert"])
    if {secret(cm, cf["tls-key"]), secret(wm, wf["tls-ca"])} != {tls_secret} or \
            tls_secret == secret(cm, cf["token-file"]):
        fail("the TLS certificate, key and CA do not come from one Secret of their own")
    if "ReadWriteMany" not in pvc["spec"]["accessModes"]:
        fail("the store claim is not ReadWriteMany")
    claims = {t["metadata"]["name"] for t in sts["spec"]["volumeClaimTemplates"]}
    if cm.get(cf["data"], {}).get("name") not in claims:
        fail("--data is not on the StatefulSet's own claim")
    return svc, sts, dep, coord, worker, cm, wm


# The "restricted" Pod Security Standard (kubernetes.io/docs/concepts/security/
# pod-security-standards), rule by rule, plus a read-only root filesystem.
RESTRICTED_VOLUMES = {"configMap", "csi", "downwardAPI", "emptyDir", "ephemeral",
                      "persistentVolumeClaim", "projected", "secret"}


def restricted(name, pod, writes):
    spec = pod["spec"]
    psc = spec.get("securityContext", {})
    for host in ("hostNetwork", "hostPID", "hostIPC"):
        if spec.get(host):
            fail(f"{name}: {host}")
    if psc.get("seccompProfile", {}).get("type") != "RuntimeDefault":
        fail(f"{name}: seccompProfile is not RuntimeDefault")
    if spec.get("automountServiceAccountToken") is not False:
        fail(f"{name}: mounts a service account token it does not use")
    for v in spec.get("volumes", []):
        kinds = set(v) - {"name"}
        if not kinds <= RESTRICTED_VOLUMES:
            fail(f"{name}: volume {v['name']} of a type restricted forbids: {kinds}")
    for c in spec["containers"]:
        sc = c.get("securityContext", {})
        where = f"{name}.{c['name']}"
        if not (sc.get("runAsNonRoot", psc.get("runAsNonRoot")) is True):
            fail(f"{where}: runAsNonRoot is not true")
        if sc.get("runAsUser", psc.get("runAsUser", 1)) == 0:
            fail(f"{where}: runs as uid 0")
        if sc.get("allowPrivilegeEscalation") is not False:
            fail(f"{where}: allowPrivilegeEscalation is not false")
        if sc.get("privileged"):
            fail(f"{where}: privileged")
        caps = sc.get("capabilities", {})
        if "ALL" not in caps.get("drop", []) or set(caps.get("add", [])) - {"NET_BIND_SERVICE"}:
            fail(f"{where}: capabilities are not drop ALL")
        if sc.get("readOnlyRootFilesystem") is not True:
            fail(f"{where}: the root filesystem is writable")
        for p in c.get("ports", []):
            if "hostPort" in p:
                fail(f"{where}: hostPort")
        # Every directory the program writes is a writable emptyDir or claim.
        m = mounts(spec, c)
        templates = {t["metadata"]["name"] for t in
                     pod.get("volumeClaimTemplates", [])}
        for path in writes(c):
            mount = next((mp for mp in sorted(m, key=len, reverse=True)
                          if path == mp or path.startswith(mp.rstrip("/") + "/")), None)
            vol = m.get(mount, {})
            writable = "emptyDir" in vol or "persistentVolumeClaim" in vol or vol.get("name") in templates
            ro = any(vm.get("readOnly") for vm in c["volumeMounts"] if vm["mountPath"] == mount)
            if mount is None or not writable or ro:
                fail(f"{where}: writes {path} but it is not on a writable emptyDir or claim")
        res = c.get("resources", {})
        for kind in ("requests", "limits"):
            for r in ("cpu", "memory"):
                if r not in res.get(kind, {}):
                    fail(f"{where}: no {kind}.{r}")
        if str(res["requests"]["memory"]) != str(res["limits"]["memory"]):
            fail(f"{where}: memory requests differ from limits (an OOM kill under pressure)")


def writes_coordinator(c):
    f = flags(c)
    return [f["data"], f["store-root"], "/tmp"]


def writes_worker(c):
    f = flags(c)
    return [f["store-root"], "/tmp"]


def policy(docs, svc, sts, dep, coord, worker):
    cpod, wpod = sts["spec"]["template"], dep["spec"]["template"]
    ns = one(docs, "Namespace")
    if ns["metadata"].get("labels", {}).get("pod-security.kubernetes.io/enforce") != "restricted":
        fail("the namespace does not enforce the restricted Pod Security Standard")
    restricted("coordinator", {**cpod, "volumeClaimTemplates": sts["spec"]["volumeClaimTemplates"]},
               writes_coordinator)
    restricted("worker", wpod, writes_worker)

    # Probes: the coordinator's are the kubelet's built-in grpc probe, on the
    # port of --health-listen (plain text: the probe speaks no TLS).
    cf = flags(coord)
    if "health-listen" not in cf:
        fail("the coordinator has no --health-listen for the grpc probes")
    hport = int(cf["health-listen"].rsplit(":", 1)[1])
    if hport == int(cf["listen"].rsplit(":", 1)[1]):
        fail("the grpc probe port is the TLS gRPC port: the kubelet's probe speaks no TLS")
    for p in ("readinessProbe", "livenessProbe"):
        probe = coord.get(p, {})
        if probe.get("grpc", {}).get("port") != hport or "exec" in probe:
            fail(f"coordinator.{p} is not a grpc probe on the health port {hport}")
    # Readiness is the overall status (NOT_SERVING on a full --data disk);
    # liveness the service that stays SERVING then (coordinator/service/coordinator.h).
    if coord["readinessProbe"]["grpc"].get("service", "") != "":
        fail("coordinator.readinessProbe does not ask the overall health status")
    if coord["livenessProbe"]["grpc"].get("service") != LIVENESS_SERVICE:
        fail(f"coordinator.livenessProbe does not ask the service {LIVENESS_SERVICE!r}: a full "
             "disk would restart the pod")
    if any(p in worker for p in ("readinessProbe", "livenessProbe", "startupProbe")) and \
            any("exec" in worker[p] for p in worker if p.endswith("Probe")):
        fail("a worker probe runs a command: probes are the kubelet's own")

    # Grace periods: within the cluster autoscaler's 600 s, and a worker's
    # longer than a lease (a drain outlasts the lease it still holds).
    lease = float(cf["lease-seconds"])
    for name, pod in (("coordinator", cpod), ("worker", wpod)):
        grace = pod["spec"].get("terminationGracePeriodSeconds", 30)
        if grace > 600:
            fail(f"{name} grace period {grace} s is above the cluster autoscaler's 600 s")
    if wpod["spec"]["terminationGracePeriodSeconds"] <= lease:
        fail("the workers' grace period is not longer than a lease")

    # Scrape: annotations on the coordinator's pods name the --http port and
    # https (the monitor serves TLS with --tls-cert).
    ann = cpod["metadata"].get("annotations", {})
    http_port = int(cf["http"].rsplit(":", 1)[1])
    if ann.get("prometheus.io/scrape") != "true" or ann.get("prometheus.io/port") != str(http_port) \
            or ann.get("prometheus.io/path") != "/metrics" or ann.get("prometheus.io/scheme") != "https":
        fail(f"the coordinator's scrape annotations do not point at https://:{http_port}/metrics: {ann}")
    with open(os.path.join(K8S, "examples", "servicemonitor.yaml")) as f:
        sm = yaml.safe_load(f)
    if sm["kind"] != "ServiceMonitor" or not selects(sm["spec"]["selector"]["matchLabels"],
                                                     svc["metadata"]["labels"]):
        fail("the ServiceMonitor example does not select the coordinator's Service")
    ep = sm["spec"]["endpoints"][0]
    if ep["port"] not in {p["name"] for p in svc["spec"]["ports"]} or ep["port"] != "http" or \
            ep["path"] != "/metrics" or ep["scheme"] != "https":
        fail("the ServiceMonitor does not scrape the Service's http port over https")

    # Disruption: a budget selects the workers, none the coordinator.
    pdbs = [d for d in docs if d["kind"] == "PodDisruptionBudget"]
    if not any(selects(p["spec"]["selector"]["matchLabels"], wpod["metadata"]["labels"]) and
               ("maxUnavailable" in p["spec"] or "minAvailable" in p["spec"]) for p in pdbs):
        fail("no PodDisruptionBudget covers the workers")

    # NetworkPolicy: every pod selected for Ingress and Egress; the
    # coordinator's gRPC port admits the workers, its http port someone;
    # workers may reach the coordinator's gRPC port and DNS.
    nps = [d for d in docs if d["kind"] == "NetworkPolicy"]
    def covering(pod):
        found = [n for n in nps if selects(n["spec"]["podSelector"].get("matchLabels", {}),
                                           pod["metadata"]["labels"])]
        if not found or not {"Ingress", "Egress"} <= set(found[0]["spec"].get("policyTypes", [])):
            fail(f"no NetworkPolicy restricts both directions of {pod['metadata']['labels']}")
        return found[0]["spec"]
    cnp, wnp = covering(cpod), covering(wpod)
    grpc_port = int(cf["listen"].rsplit(":", 1)[1])
    def admits(rules, peer_labels, port, key):
        for r in rules:
            ports = {p.get("port") for p in r.get("ports", [])}
            peers = r.get(key, [])
            if ports and port not in ports:
                continue
            if not peers or any(selects(p.get("podSelector", {}).get("matchLabels", {}), peer_labels)
                                and "podSelector" in p for p in peers):
                return True
        return False
    if not admits(cnp.get("ingress", []), wpod["metadata"]["labels"], grpc_port, "from"):
        fail("the coordinator's NetworkPolicy does not admit the workers on its gRPC port")
    if not any(http_port in {p.get("port") for p in r.get("ports", [])} for r in cnp.get("ingress", [])):
        fail("the coordinator's NetworkPolicy admits nobody on its http port (Prometheus)")
    if wnp.get("ingress"):
        fail("workers serve nothing but their NetworkPolicy admits ingress")
    if not admits(wnp.get("egress", []), cpod["metadata"]["labels"], grpc_port, "to"):
        fail("the workers' NetworkPolicy does not let them reach the coordinator")
    if not any(53 in {p.get("port") for p in r.get("ports", [])} for r in wnp.get("egress", [])):
        fail("the workers' NetworkPolicy does not let them resolve the Service's name")


def images(docs, coord, worker):
    """Images set through kustomize images: with the project's version as tag."""
    with open(os.path.join(K8S, "kustomization.yaml")) as f:
        kust = yaml.safe_load(f)
    with open(os.path.join(SRC, "CMakeLists.txt")) as f:
        version = re.search(r"project\(wavebake VERSION ([0-9.]+)", f.read()).group(1)
    entries = {i["name"]: i for i in kust.get("images", [])}
    for c in (coord, worker):
        image = c["image"]
        if ":" in image or "@" in image:
            fail(f"{c['name']}: image {image} carries its own tag; kustomize images: sets it")
        if image not in entries:
            fail(f"{c['name']}: image {image} is not in kustomization.yaml's images:")
        tag = str(entries[image].get("newTag", ""))
        if tag != version:
            fail(f"kustomize images: tags {image} {tag!r}, not the project's version {version}")
    return version


# Packages a build stage may hold but a runtime image may not.
BUILD_ONLY = re.compile(r"(-dev$|^build-essential$|^cmake$|^ninja-build$|^gcc|^g\+\+|^clang|"
                        r"^chromium|^slurm|^munge$|^protobuf-compiler|^git$|^python3|^pkg-config$)")


def stages(path):
    """The Dockerfile's stages: [(FROM line, [lines])], continuations joined."""
    with open(path) as f:
        text = re.sub(r"\\\n", " ", f.read())
    out = []
    for line in text.splitlines():
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        if line.upper().startswith("FROM "):
            out.append((line, []))
        elif out:
            out[-1][1].append(line)
    return out


def installed(lines):
    pkgs = []
    for line in lines:
        for m in re.finditer(r"apt-get install ((?:-\S+\s+)*)([^&]+)", line):
            pkgs += m.group(2).split()
    return pkgs


def dockerfile():
    st = stages(os.path.join(K8S, "Dockerfile"))
    if len(st) < 2:
        fail("the Dockerfile has one stage: its runtime image would hold the build tools")
    runtime_from, runtime = st[-1]
    build_name = st[0][0].split()[-1]
    pkgs = installed(runtime)
    if not pkgs:
        fail("the runtime stage installs no runtime libraries")
    if bad := [p for p in pkgs if BUILD_ONLY.search(p)]:
        fail(f"the runtime stage installs build-only packages: {bad}")
    copies = [l for l in runtime if l.upper().startswith("COPY")]
    if copies != [f"COPY --from={build_name} /build/wavebake /usr/local/bin/wavebake"]:
        fail(f"the runtime stage copies more than the binary from {build_name}: {copies}")
    if not any(re.fullmatch(r"USER [1-9][0-9]*:[1-9][0-9]*", l) for l in runtime):
        fail("the runtime stage does not run as a numeric non-root user")
    # Every library the binary loads comes from a listed package or one apt
    # installs with them (or the base image's required packages).
    ldd = subprocess.run(["ldd", WB], capture_output=True, text=True, check=True).stdout
    libs = sorted({m.group(1) for m in re.finditer(r"=> (/\S+)", ldd)})
    # Which package ships each file: dpkg's own lists, read once (one
    # `dpkg -S` per library takes seconds on a loaded machine).
    shipped = {}
    info = "/var/lib/dpkg/info"
    for name in os.listdir(info):
        if name.endswith(".list"):
            with open(os.path.join(info, name), errors="replace") as f:
                for line in f:
                    if ".so" in line:
                        shipped[line.rstrip("\n")] = name[:-5].split(":")[0]
    owners = {}
    for lib in libs:
        real = os.path.realpath(lib)
        # Debian 12 is merged-/usr: dpkg knows a file by the path its package ships.
        tries = [real, lib] + [p.replace("/usr/lib/", "/lib/", 1) for p in (real, lib)]
        owner = next((shipped[p] for p in tries if p in shipped), None)
        if owner is None:
            fail(f"no Debian package owns {lib}, a library of the binary")
        owners[lib] = owner
    # debian:12-slim holds the Priority: required packages and apt; apt-get
    # brings each listed package's dependencies with it.
    prio = subprocess.run(["dpkg-query", "-W", "--showformat=${Package} ${Priority}\n"],
                          capture_output=True, text=True).stdout
    base = [l.split()[0] for l in prio.splitlines() if l.endswith(" required")] + ["apt"]
    closure = subprocess.run(["apt-cache", "depends", "--recurse", "--no-recommends", "--no-suggests",
                              "--no-conflicts", "--no-breaks", "--no-replaces", "--no-enhances"]
                             + pkgs + base, capture_output=True, text=True).stdout
    have = set(pkgs) | {l.strip() for l in closure.splitlines() if l and not l.startswith(" ")}
    missing = sorted({f"{owners[l]} ({os.path.basename(l)})" for l in libs if owners[l] not in have})
    if missing:
        fail(f"the runtime stage lacks packages the binary needs: {missing}")
    unused = [p for p in pkgs if p not in set(owners.values()) and p != "ca-certificates"]
    if unused:
        fail(f"the runtime stage installs packages no library of the binary comes from: {unused}")
    return pkgs, image_estimate(pkgs, base)


def image_estimate(pkgs, base):
    """What the runtime stage adds to debian:12-slim, from apt's metadata (no
    container runtime here): the packages of the listed ones' dependency
    closure that the base's closure lacks, their Installed-Size summed, and
    the binary stripped (as the build stage strips it)."""
    def closure(names):
        out = subprocess.run(["apt-cache", "depends", "--recurse", "--no-recommends",
                              "--no-suggests", "--no-conflicts", "--no-breaks", "--no-replaces",
                              "--no-enhances"] + names, capture_output=True, text=True).stdout
        return {l.strip() for l in out.splitlines() if l and not l.startswith((" ", "<"))}
    added = sorted(closure(pkgs) - closure(base))
    show = subprocess.run(["apt-cache", "show", "--no-all-versions"] + added,
                          capture_output=True, text=True).stdout
    kib = sum(int(k) for k in re.findall(r"^Installed-Size: (\d+)", show, re.M))
    stripped = os.path.join(TMP, "wavebake.stripped")
    subprocess.run(["strip", "-o", stripped, WB], check=True)
    return (f"{len(added)} packages beyond debian:12-slim's, {kib / 1024:.0f} MiB installed, "
            f"and the binary, {os.path.getsize(stripped) / 2**20:.1f} MiB stripped")


def readme(pkgs, version):
    """README's Kubernetes section names what the manifests hold."""
    with open(os.path.join(SRC, "README.md")) as f:
        text = f.read()
    section = text[text.index("### On Kubernetes"):]
    section = section[:section.index("\n## ")]
    m = re.search(r"runtime image holds[^:]*:(.*?)\.\s", section, re.S)
    if not m or sorted(re.findall(r"`([a-z0-9.+-]+)`", m.group(1))) != sorted(pkgs):
        fail(f"README's Kubernetes section does not list the runtime packages {sorted(pkgs)}")
    for needle in ("disruption.yaml", "network-policy.yaml", "examples/servicemonitor.yaml",
                   "wavebake-token", "wavebake-tls", "--health-listen", "--http", "600 s",
                   f"newTag", version, "restricted", f"`{LIVENESS_SERVICE}`"):
        if needle not in section:
            fail(f"README's Kubernetes section does not mention {needle}")


def expand(arg, env):
    return re.sub(r"\$\(([A-Z_]+)\)", lambda m: env[m.group(1)], arg)


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def health_check(address, service):
    """grpc.health.v1.Health/Check as the kubelet's grpc probe sends it (plain
    text), encoded by hand: HealthCheckRequest{service = 1}, and the
    response's status = 1 (1 SERVING, 2 NOT_SERVING); or the error's code."""
    import grpc
    request = b"" if not service else b"\x0a" + bytes([len(service)]) + service.encode()
    with grpc.insecure_channel(address) as channel:
        check = channel.unary_unary("/grpc.health.v1.Health/Check")
        try:
            reply = check(request, timeout=4)
        except grpc.RpcError as e:
            return str(e.code())
    return {b"\x08\x01": "SERVING", b"\x08\x02": "NOT_SERVING"}.get(reply, repr(reply))


def rehearse(coord, worker, cm, wm):
    root = {path: os.path.join(TMP, "mnt" + path.replace("/", "_")) for path in {**cm, **wm}}
    for d in root.values():
        os.makedirs(d, exist_ok=True)
    cf, wf = flags(coord), flags(worker)
    tokdir = root[os.path.dirname(cf["token-file"])]
    with open(os.path.join(tokdir, "token"), "w") as f:
        f.write("k8s-rehearsal-token\n")
    # The TLS Secret as cert-manager writes one: tls.crt, tls.key, ca.crt;
    # the certificate names the Service (and 127.0.0.1, where it is dialled here).
    tlsdir = root[os.path.dirname(cf["tls-cert"])]
    crt, key = os.path.join(tlsdir, "tls.crt"), os.path.join(tlsdir, "tls.key")
    subprocess.run(["openssl", "req", "-x509", "-newkey", "rsa:2048", "-nodes", "-days", "1",
                    "-subj", "/CN=wavebake-coordinator", "-addext",
                    "subjectAltName=DNS:wavebake-coordinator,IP:127.0.0.1",
                    "-keyout", key, "-out", crt], check=True, capture_output=True)
    with open(crt) as src, open(os.path.join(tlsdir, "ca.crt"), "w") as dst:
        dst.write(src.read())
    for f, m in ((cf, cm), (wf, wm)):
        for k in ("token-file", "tls-ca", "tls-cert", "tls-key"):
            if k in f:
                here = os.path.join(root[os.path.dirname(f[k])], os.path.basename(f[k]))
                if not os.path.exists(here):
                    src = os.path.join(tokdir if k == "token-file" else tlsdir, os.path.basename(f[k]))
                    os.symlink(src, here)

    def mapped(args, ports=None):
        out = []
        for a in args:
            for path in sorted(root, key=len, reverse=True):  # the longest mount first, once
                b = re.sub(rf"=({re.escape(path)})(/|$)", lambda m: "=" + root[path] + m.group(2), a)
                if b != a:
                    a = b
                    break
            m = re.fullmatch(r"--([a-z-]+)=(.*)", a)
            if ports and m and m.group(1) in ports:
                a = f"--{m.group(1)}={ports[m.group(1)]}"
            out.append(a)
        return out

    procs = []
    try:
        addr_file = os.path.join(TMP, "coordinator.addr")
        http_file = os.path.join(TMP, "coordinator.http")
        hport = free_port()
        args = mapped(coord["args"], {"listen": "127.0.0.1:0", "http": "127.0.0.1:0",
                                      "health-listen": f"127.0.0.1:{hport}"})
        clog = open(os.path.join(TMP, "k8s-coordinator.log"), "w")
        procs.append(subprocess.Popen([WB] + args + [f"--address-file={addr_file}",
                                                     f"--http-address-file={http_file}"],
                                      stdout=clog, stderr=subprocess.STDOUT))
        deadline = time.time() + 20
        while not all(os.path.exists(p) and open(p).read().strip() for p in (addr_file, http_file)):
            if time.time() > deadline or procs[0].poll() is not None:
                fail("the coordinator's container args do not start a coordinator")
            time.sleep(0.1)
        addr = open(addr_file).read().strip()
        http_addr = open(http_file).read().strip()
        # The kubelet's grpc probes: grpc.health.v1 Check in plain text on the
        # probe's port, each with the service its probe names.
        for p in ("readinessProbe", "livenessProbe"):
            service = coord[p]["grpc"].get("service", "")
            status = health_check(f"127.0.0.1:{hport}", service)
            if status != "SERVING":
                fail(f"the {p} (grpc, port {hport}, service {service!r}) answers {status}")
        # The TLS port refuses plain text: tokens never cross in the clear.
        r = subprocess.run([WB, "health", f"--coordinator={addr}", "--timeout=2"],
                           capture_output=True, text=True, timeout=30)
        if r.returncode == 0:
            fail("the coordinator's gRPC port answers in plain text")
        ca = os.path.join(tlsdir, "ca.crt")
        token = ["--coordinator", addr, "--token-file", os.path.join(tokdir, "token"), "--tls-ca", ca]
        # A scrape as the annotations describe it: https, the port's /metrics, the token.
        ctx = ssl.create_default_context(cafile=ca)
        req = urllib.request.Request(f"https://{http_addr}/metrics",
                                     headers={"Authorization": "Bearer k8s-rehearsal-token"})
        with urllib.request.urlopen(req, context=ctx, timeout=10) as resp:
            if resp.status != 200 or b"wavebake_build_info" not in resp.read():
                fail("/metrics does not answer a scrape over https with the token")
        env = {"WB_THREADS": "2", "POD_NAME": "wavebake-worker-rehearsal"}
        wlog_path = os.path.join(TMP, "k8s-worker.log")
        wlog = open(wlog_path, "w")
        wargs = [expand(a, env) for a in mapped(worker["args"], {"coordinator": addr})]
        procs.append(subprocess.Popen([WB] + wargs, stdout=wlog, stderr=subprocess.STDOUT))
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
svc, sts, dep, coord, worker, cm, wm = wiring(docs)
policy(docs, svc, sts, dep, coord, worker)
version = images(docs, coord, worker)
pkgs, estimate = dockerfile()
readme(pkgs, version)
rehearse(coord, worker, cm, wm)
print(f"PASS: {len(docs)} manifests valid against python3-kubernetes' API models; wiring, "
      "restricted PSS, resources, probes, grace, scrape, PDB, NetworkPolicy, images, TLS, "
      f"Dockerfile ({len(pkgs)} runtime packages cover ldd) checked; coordinator, probes and "
      f"worker rehearsed from their own args. Runtime image: debian:12-slim + {estimate}")
