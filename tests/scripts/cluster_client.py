"""A Python client of wavebake.v1.JobService (DESIGN.md §4), generated from
proto/wavebake.proto by the test: submit a bake, watch it to the end, fetch
the finished store with ReadStore, and open it with zarr.

    cluster_client.py GENERATED_DIR ADDRESS TOKEN_FILE OUT_DIR
"""
import os
import sys

sys.path.insert(0, sys.argv[1])
import grpc  # noqa: E402
import numpy as np  # noqa: E402
import zarr  # noqa: E402

import wavebake_pb2 as pb  # noqa: E402
import wavebake_pb2_grpc as rpc  # noqa: E402

address, token_file, out = sys.argv[2], sys.argv[3], sys.argv[4]
with open(token_file) as f:
    metadata = [("authorization", "Bearer " + f.readline().strip())]
jobs = rpc.JobServiceStub(grpc.insecure_channel(address))

# A scene uploaded by content (one chunk: the file name, then the bytes).
obj = b"v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv 0 0.6 0\nf 1 3 2\nf 1 4 3\nf 1 2 5\nf 2 3 5\n"
ref = jobs.UploadScene(iter([pb.SceneChunk(file_name="tent.obj", data=obj)]), metadata=metadata)
assert len(ref.sha256) == 64 and ref.size == len(obj), ref

request = pb.BakeRequest(scene=pb.SceneSource(uploaded=ref), light_res=8, layout="hilbert:4x2",
                         output_name="tent.wbk")
job = jobs.Submit(request, metadata=metadata)
# Tiles, groups, FINALIZE's shards (one per group, at most 64) and its last task.
assert job.phase == pb.PHASE_QUEUED and \
    job.tasks_total == job.tiles + job.groups + min(job.groups, 64) + 1, job
assert job.request.column_mode == "adaptive", "Submit fills in the defaults"

phases = []
for event in jobs.Watch(pb.JobId(id=job.id), metadata=metadata, timeout=120):
    if event.kind == pb.EVENT_PHASE:
        phases.append(pb.Phase.Name(event.phase))
assert phases == ["PHASE_BAKING", "PHASE_TRANSFORMING", "PHASE_FINALIZING", "PHASE_DONE"], phases
done = jobs.Get(pb.JobId(id=job.id), metadata=metadata)
assert done.phase == pb.PHASE_DONE and done.tasks_done == done.tasks_total, done
assert done.rays_traced > 0 and done.stats_json, done

files = {}
for chunk in jobs.ReadStore(pb.JobId(id=job.id), metadata=metadata, timeout=120):
    data = files.setdefault(chunk.path, bytearray())
    assert chunk.offset == len(data), (chunk.path, chunk.offset)
    data.extend(chunk.data)
    if chunk.last:
        assert len(data) == chunk.file_size, chunk.path
for path, data in files.items():
    os.makedirs(os.path.dirname(os.path.join(out, path)), exist_ok=True)
    with open(os.path.join(out, path), "wb") as f:
        f.write(data)

store = zarr.open(out, mode="r")
assert store.attrs["format"] == "wavebake/2", dict(store.attrs)
indptr = store["transport/indptr"][:]
columns = 6 * 8 * 8
assert indptr.shape == (columns + 1,) and indptr[0] == 0 and np.all(np.diff(indptr) >= 0)
assert store["transport/data"].shape == (indptr[-1],)
assert store["transport/indices"].shape == (indptr[-1],)
grid = store["samples/grid"][:]
assert grid.shape == (2, 4) and sorted(grid.ravel().tolist()) == [-1, -1, -1, 0, 1, 2, 3, 4]
assert store["samples/position"].shape == (5, 3)
print("python client: job", job.id, "DONE,", len(files), "files,", int(indptr[-1]), "coefficients")
