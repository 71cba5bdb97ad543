#!/usr/bin/env python3
"""Checks a kustomization of deploy/k8s/ (deploy/k8s for one run,
deploy/k8s/campaign for a campaign) for consistency and prints its commands
for a local run.

    k8s_commands.py DIR check
    k8s_commands.py DIR master-script   # the master container's sh script
    k8s_commands.py DIR worker-args     # the worker container's argv, one per line

The check: kustomization lists two manifests, the master's (a Service and a
StatefulSet) and the workers' (a Deployment); one master (StatefulSet of 1)
whose Service port, container port and bind port agree; workers connect
to that Service and port; every file a command names under /keys, /config
or /data is mounted there (and, for /keys, projected from the Secret).
Exits 1 with the reason on any mismatch.
"""

import re
import sys

import yaml


def load(directory, name):
    with open(f"{directory}/{name}") as f:
        return [d for d in yaml.safe_load_all(f) if d]


def fail(message):
    sys.exit(f"k8s_commands: {message}")


def by_kind(docs, kind):
    found = [d for d in docs if d.get("kind") == kind]
    if len(found) != 1:
        fail(f"expected one {kind}, found {len(found)}")
    return found[0]


def main():
    directory, what = sys.argv[1], sys.argv[2]
    kustomization = load(directory, "kustomization.yaml")[0]
    resources = kustomization.get("resources", [])
    if len(resources) != 2:
        fail("kustomization.yaml must list the master's and the workers' "
             "manifests")
    manifests = [load(directory, name) for name in resources]
    kinds = [{d.get("kind") for d in docs} for docs in manifests]
    if "StatefulSet" in kinds[1]:
        manifests.reverse()
    master_docs, worker_docs = manifests
    service = by_kind(master_docs, "Service")
    master = by_kind(master_docs, "StatefulSet")
    workers = by_kind(worker_docs, "Deployment")
    master_pod = master["spec"]["template"]["spec"]
    worker_pod = workers["spec"]["template"]["spec"]
    master_container = master_pod["containers"][0]
    worker_container = worker_pod["containers"][0]
    script = master_container["command"][2]
    args = worker_container["command"]

    if what == "master-script":
        print(script)
        return
    if what == "worker-args":
        print("\n".join(args))
        return

    if master["spec"]["replicas"] != 1:
        fail("the master must be a single replica (one master per store)")
    if master_container["command"][:2] != ["/bin/sh", "-c"]:
        fail("the master's command must be /bin/sh -c SCRIPT")
    port = service["spec"]["ports"][0]["port"]
    target = service["spec"]["ports"][0]["targetPort"]
    container_port = master_container["ports"][0]["containerPort"]
    binds = set(re.findall(r"--bind tcp://0\.0\.0\.0:(\d+)", script))
    if binds != {str(container_port)} or target != container_port:
        fail(f"ports disagree: service {port}->{target}, container "
             f"{container_port}, bind {sorted(binds)}")
    if service["spec"]["selector"] != master["spec"]["template"]["metadata"]["labels"]:
        fail("the Service does not select the master pod")
    connect = args[args.index("--connect") + 1]
    if connect != f"tcp://{service['metadata']['name']}:{port}":
        fail(f"workers connect to {connect}, not the master's Service")
    for flag in ("--curve-secret", "--curve-allow"):
        if flag not in script:
            fail(f"the master listens beyond loopback without {flag}")
    for flag in ("--curve-server", "--curve-secret"):
        if flag not in args:
            fail(f"the workers lack {flag}")

    def check_files(pod, container, text, who):
        mounts = {m["mountPath"]: m["name"] for m in container["volumeMounts"]}
        volumes = {v["name"]: v for v in pod["volumes"]}
        templates = {t["metadata"]["name"] for t in
                     master["spec"].get("volumeClaimTemplates", [])}
        for path in sorted(set(re.findall(r"/(?:keys|config|data)/[\w.-]+", text))):
            mount = "/" + path.split("/")[1]
            if mount not in mounts:
                fail(f"{who} uses {path} but nothing is mounted at {mount}")
            name = mounts[mount]
            volume = volumes.get(name)
            if volume is None:
                if who == "master" and name in templates:
                    continue
                fail(f"{who}: volume {name} is not defined")
            if "secret" in volume:
                items = {i["path"] for i in volume["secret"].get("items", [])}
                if path.split("/")[2] not in items:
                    fail(f"{who} uses {path}, which the Secret does not project")

    check_files(master_pod, master_container, script, "master")
    check_files(worker_pod, worker_container, " ".join(args), "worker")
    print("k8s_commands: manifests consistent")


if __name__ == "__main__":
    main()
