#!/usr/bin/env bash
# The proto compiles with Debian's python3-grpc-tools (1.14, whose protoc predates
# proto3 `optional`) as well as with protoc + grpc_python_plugin, and the stubs it
# makes load under Debian's python3-protobuf and python3-grpcio.
#   grpc_tools_compile.sh SOURCE_DIR
set -euo pipefail
SRC="$1"
OUT="$(mktemp -d /tmp/alignset-grpc-tools-XXXXXX)"
trap 'rm -rf "$OUT"' EXIT
/usr/bin/python3 -m grpc_tools.protoc -I"$SRC/proto" --python_out="$OUT" --grpc_python_out="$OUT" \
  "$SRC/proto/alignset/v1/alignset.proto"
touch "$OUT/alignset/__init__.py" "$OUT/alignset/v1/__init__.py"
PYTHONPATH="$OUT" /usr/bin/python3 - <<'PY'
from alignset.v1 import alignset_pb2 as pb, alignset_pb2_grpc
r = pb.SamplesRequest(sampler="owen-sobol", n=64)
assert not r.HasField("shear_deg")
r.shear_deg = 30.0
assert r.HasField("shear_deg")
assert pb.SamplesRequest.FromString(r.SerializeToString()).shear_deg == 30.0
assert hasattr(alignset_pb2_grpc, "AlignSetStub")
print("grpc_tools.protoc: alignset.proto compiles and its stubs load")
PY
