"""Python client of alignset-server: optimized, direction-aligned anisotropic
sampling point sets as NumPy arrays.

    import alignset
    with alignset.Client("127.0.0.1:50051") as client:
        points = client.get(1024, 30)            # (1024, 2) float64 in [0, 1)
        sets = client.get_many([(1024, 30), (4096, (12, 100))])
        space = client.get_space(256)            # (46, 256, 2): directions 0..45

Angles are degrees and name the spectral direction: the normal of the
integrand's edge. Runtime needs Debian's python3-grpcio, python3-protobuf and
python3-numpy; the gRPC stubs (alignset.v1) are generated at build time by
protoc and grpc_python_plugin (see docs/usage.md, "Python").
"""

from alignset.client import AlignedSet, AlignSetError, Client, lattice_points

__all__ = ["AlignedSet", "AlignSetError", "Client", "lattice_points"]
