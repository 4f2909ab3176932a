"""The client: one gRPC channel to alignset-server, points as NumPy arrays."""

import dataclasses
import math
import threading
import time

import grpc
import numpy as np

from alignset.v1 import alignset_pb2 as pb
from alignset.v1 import alignset_pb2_grpc as pb_grpc

DEFAULT_SERVER = "127.0.0.1:50051"


class AlignSetError(Exception):
    """A refused or failed call (or batch item): `code` is a grpc.StatusCode."""

    def __init__(self, code, message):
        super().__init__("%s: %s" % (code.name, message))
        self.code = code
        self.message = message


@dataclasses.dataclass
class AlignedSet:
    """A served set: `points` is an (N, 2) float64 array in [0, 1)^2;
    `metadata` the server's alignset.v1.SetMetadata (served directions,
    canonical key, swap / invert, losses, profile, from_cache, ...)."""

    points: np.ndarray
    metadata: object

    def pixel_points(self, shift):
        """A pixel's own randomization of this set under `shift` in [0, 1)^2
        (one uniform shift per pixel): a lattice or tent-lattice rebuilt from
        its generator with the shift before the fold (lattice_points), any
        other set shifted on the torus. Unbiased either way; a tent-lattice
        from a server too old to tell its generator is shifted on the torus
        too, and then integrates smooth non-periodic shading only about as
        well as Owen-Sobol. The sampler library's SetPixelPoints does the same
        in C++ (<alignset/aligned_sampler.h>)."""
        sx, sy = (float(v) for v in shift)
        if not (0.0 <= sx < 1.0 and 0.0 <= sy < 1.0):
            raise ValueError("shift must lie in [0, 1)^2")
        construction = getattr(self.metadata, "construction", "")
        generator = getattr(self.metadata, "lattice_generator", 0)
        if construction in ("lattice", "tent-lattice") and generator:
            return lattice_points(len(self.points), generator, (sx, sy),
                                  construction == "tent-lattice")
        pts = self.points + np.array([sx, sy])
        return np.where(pts >= 1.0, pts - 1.0, pts)


def lattice_points(n, generator, shift, folded):
    """Points of a served lattice under a shift of your own: the rank-1
    lattice frac(i (1, generator) / n + shift), i < n, folded by the tent
    1 - |2u - 1| after the shift when `folded` (a "tent-lattice").

    The served set's generator is `metadata.lattice_generator` (0 for other
    constructions). A renderer that randomizes each pixel draws a uniform
    shift in [0, 1)^2 per pixel and builds the points here: for a
    tent-lattice, shifting before the fold keeps its gain on smooth
    functions that a shift of the served (folded) points loses. Returns an
    (n, 2) float64 array in [0, 1)^2, by the same recipe as the C++ header
    <alignset/lattice_points.h>."""
    n = int(n)
    generator = int(generator)
    if n < 1 or not 0 < generator < max(n, 2) or math.gcd(generator, n) != 1:
        raise ValueError("need n >= 1 and a generator coprime to n in [1, n)")
    sx, sy = (float(v) for v in shift)
    if not (0.0 <= sx < 1.0 and 0.0 <= sy < 1.0):
        raise ValueError("shift must lie in [0, 1)^2")
    i = np.arange(n, dtype=np.uint64)
    x = i.astype(np.float64) * (1.0 / n) + sx
    y = ((i * np.uint64(generator)) % np.uint64(n)).astype(np.float64) * (1.0 / n) + sy
    pts = np.stack([x - np.floor(x), y - np.floor(y)], axis=1)
    if folded:
        pts = np.minimum(1.0 - np.abs(2.0 * pts - 1.0), np.nextafter(1.0, 0.0))
    return pts


def _points(data, n):
    # 16 bytes per point, little-endian float64, x0 y0 x1 y1 ...
    if len(data) != 16 * n:
        raise AlignSetError(grpc.StatusCode.INTERNAL,
                            "%d bytes of points for n = %d" % (len(data), n))
    return np.frombuffer(data, dtype="<f8").reshape(n, 2).copy()


def _directions(directions):
    if isinstance(directions, (int, float)):
        return [float(directions)]
    return [float(d) for d in directions]


def _request(n, directions, realization=0, construction=""):
    return pb.AlignedSetRequest(n=int(n), directions_deg=_directions(directions),
                                realization=int(realization), construction=construction or "")


def _checked(aligned, construction):
    # A server from before constructions ignores the field and answers with
    # an optimized set: refuse it rather than pass it off as a lattice or net.
    asked = construction or "optimized"
    got = aligned.metadata.construction or "optimized"
    if got != asked:
        raise AlignSetError(grpc.StatusCode.FAILED_PRECONDITION,
                            "asked for construction '%s', the server answered '%s' "
                            "(a server without constructions: update it)" % (asked, got))
    return aligned


def _aligned(response):
    return AlignedSet(_points(response.points, response.n), response.metadata)


_CODES = {c.value[0]: c for c in grpc.StatusCode}


def _valid_seconds(t):
    return (isinstance(t, (int, float)) and not isinstance(t, bool) and math.isfinite(t)
            and t >= 0)


def _check_timeout(timeout):
    """A call's deadline: None (none) or a finite number of seconds >= 0."""
    if timeout is not None and not _valid_seconds(timeout):
        raise ValueError("timeout must be None or a finite number of seconds >= 0")


class Client:
    """A connection to alignset-server.

    server: "host:port" (default 127.0.0.1:50051); timeout: default deadline of
    each call in seconds (None: none; every method also takes its own);
    token: sent as "authorization: Bearer <token>"; root_certificates: PEM
    bytes to trust, which switches to TLS; connect_timeout: how long a call
    waits for the connection, a call whose connection failed being sent again
    once the server is back (a restart, a full accept backlog), as the C++
    client does (0: no wait)."""

    def __init__(self, server=DEFAULT_SERVER, timeout=None, token=None, root_certificates=None,
                 connect_timeout=2.0):
        if not _valid_seconds(connect_timeout):
            raise ValueError("connect_timeout must be a finite number of seconds >= 0")
        _check_timeout(timeout)
        # Reconnect soon after a failed attempt (gRPC's default waits a second).
        options = [("grpc.max_receive_message_length", -1),
                   ("grpc.initial_reconnect_backoff_ms", 100),
                   ("grpc.min_reconnect_backoff_ms", 100),
                   ("grpc.max_reconnect_backoff_ms", 1000)]
        if root_certificates is not None:
            creds = grpc.ssl_channel_credentials(root_certificates=root_certificates)
            self._channel = grpc.secure_channel(server, creds, options=options)
        else:
            self._channel = grpc.insecure_channel(server, options=options)
        self._stub = pb_grpc.AlignSetStub(self._channel)
        self._timeout = timeout
        self._connect_timeout = connect_timeout
        self._metadata = [("authorization", "Bearer " + token)] if token else None
        # The channel's connectivity as gRPC last reported it; subscribed with
        # try_to_connect, the channel connects, and reconnects when it drops.
        self._state = grpc.ChannelConnectivity.IDLE
        self._state_changed = threading.Condition()
        self._channel.subscribe(self._on_state, try_to_connect=True)

    def _on_state(self, state):
        with self._state_changed:
            self._state = state
            self._state_changed.notify_all()

    def _await_connection(self, by):
        """Waits until `by` for the connection; whether it is ready."""
        if self._connect_timeout <= 0:
            return False
        with self._state_changed:
            while self._state != grpc.ChannelConnectivity.READY:
                left = by - time.monotonic()
                if left <= 0:
                    return False
                if self._state in (grpc.ChannelConnectivity.IDLE,
                                   grpc.ChannelConnectivity.TRANSIENT_FAILURE):
                    # gRPC's Python channel asks for a connection once per
                    # subscription, and an idle one does not reconnect alone.
                    self._channel.subscribe(self._ignore_state, try_to_connect=True)
                    self._channel.unsubscribe(self._ignore_state)
                self._state_changed.wait(timeout=min(left, 0.2))
            return True

    @staticmethod
    def _ignore_state(state):
        pass

    def close(self):
        self._channel.unsubscribe(self._on_state)
        # gRPC Python polls the connectivity on a thread of its own, every
        # 0.2 s while anyone listens or a connection was asked for, and raises
        # "Channel closed!" there if the channel closes under it (grpc issue
        # 18995): a traceback on stderr after every script. Let it see that
        # nobody listens first. Its state is private: where it is missing the
        # close goes ahead.
        poller = getattr(self._channel, "_connectivity_state", None)
        until = time.monotonic() + 1.0
        while getattr(poller, "polling", False) and time.monotonic() < until:
            time.sleep(0.01)
        self._channel.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _call(self, method, request, timeout):
        _check_timeout(timeout)
        timeout = self._timeout if timeout is None else timeout
        start = time.monotonic()
        connect_by = start + (self._connect_timeout if timeout is None
                              else min(self._connect_timeout, timeout))
        self._await_connection(connect_by)
        while True:
            left = None if timeout is None else max(0.0, timeout - (time.monotonic() - start))
            try:
                return method(request, timeout=left, metadata=self._metadata)
            except grpc.RpcError as e:
                # Sent again only when the connection failed (the channel is
                # not ready): an UNAVAILABLE the server sent is final. The
                # channel's news arrives on another thread: give it a moment.
                connected = False
                if e.code() == grpc.StatusCode.UNAVAILABLE:
                    with self._state_changed:
                        connected = not self._state_changed.wait_for(
                            lambda: self._state != grpc.ChannelConnectivity.READY, timeout=0.2)
                if (e.code() != grpc.StatusCode.UNAVAILABLE or connected
                        or time.monotonic() >= connect_by or not self._await_connection(connect_by)):
                    raise AlignSetError(e.code(), e.details()) from None

    def get_set(self, n, directions, realization=0, timeout=None, construction=None):
        """The aligned set for n points and one or two directions (degrees),
        with its metadata. `realization` (0..63) picks one of the key's
        independent sets; 0 is the key's first. `construction`: None or
        "optimized" (the default, the optimized sets), "lattice" (an aligned
        rank-1 lattice), "tent-lattice" (that lattice folded by 1 - |2u - 1|
        after its shift) or "net" (an aligned (0,m,2)-net, n a power of two),
        each cached apart from the others. Blocks while the server
        optimizes a missing set."""
        request = _request(n, directions, realization, construction)
        return _checked(_aligned(self._call(self._stub.GetAlignedSet, request, timeout)),
                        construction)

    def get(self, n, directions, realization=0, timeout=None, construction=None):
        """The points alone: an (n, 2) float64 array."""
        return self.get_set(n, directions, realization, timeout, construction).points

    def get_many(self, items, timeout=None, construction=None):
        """Many sets in one call: items are (n, directions) or (n, directions,
        realization) tuples, all of one `construction` (as in get_set).
        Returns one entry per item, in order: an AlignedSet, or the
        AlignSetError of that item (not raised: the other items stand)."""
        request = pb.AlignedSetsRequest(
            items=[_request(*item, construction=construction) for item in items])
        return self._batch(request, timeout, construction)

    def get_realizations(self, n, directions, count, timeout=None, construction=None):
        """Realizations 0..count-1 of one key as a (count, n, 2) array, in one
        call (the server optimizes the missing ones in parallel)."""
        results = self.get_many([(n, directions, r) for r in range(count)], timeout, construction)
        for r in results:
            if isinstance(r, AlignSetError):
                raise r
        return np.stack([r.points for r in results])

    def get_space(self, n, realization=0, timeout=None, construction=None):
        """The 46 canonical one-direction sets of n points (directions 0..45
        degrees) as one (46, n, 2) array; every other direction is one of them
        swapped and / or mirrored."""
        request = pb.AlignedSetsRequest(space=pb.ONE_DIRECTION, space_n=int(n),
                                        space_realization=int(realization),
                                        space_construction=construction or "")
        results = self._batch(request, timeout, construction)
        for r in results:
            if isinstance(r, AlignSetError):
                raise r
        return np.stack([r.points for r in results])

    def _batch(self, request, timeout, construction=None):
        response = self._call(self._stub.GetAlignedSets, request, timeout)
        out = []
        for item in response.items:
            if item.code != 0:
                out.append(AlignSetError(_CODES.get(item.code, grpc.StatusCode.UNKNOWN), item.message))
            else:
                try:
                    out.append(_checked(_aligned(item.set), construction))
                except AlignSetError as e:
                    out.append(e)
        return out

    def estimate_direction(self, values, points=None, second=False, timeout=None):
        """The principal direction(s) of an integrand (EstimateDirection):
        `values` an (H, W) grid with values[j, i] = f((i + 1/2) / W,
        (j + 1/2) / H) (rows along y), or, with `points` an (m, 2) array in
        [0, 1]^2, the m sample values f(points[j]). Returns the
        alignset.v1.EstimateDirectionResponse: first.status is DIRECTION_FOUND
        or NO_DOMINANT_DIRECTION (then first.reason says why), first.theta_deg
        the edge normal to ask get() for."""
        values = np.asarray(values, dtype=np.float64)
        request = pb.EstimateDirectionRequest(second=bool(second))
        if points is None:
            if values.ndim != 2:
                raise AlignSetError(grpc.StatusCode.INVALID_ARGUMENT,
                                    "a grid of values has shape (H, W), not %s" % (values.shape,))
            request.grid.height, request.grid.width = values.shape
            request.grid.values.extend(values.ravel().tolist())
        else:
            points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
            request.samples.x.extend(points[:, 0].tolist())
            request.samples.y.extend(points[:, 1].tolist())
            request.samples.f.extend(values.ravel().tolist())
        return self._call(self._stub.EstimateDirection, request, timeout)

    def samples(self, sampler, n, seed=1, shear=None, timeout=None):
        """A baseline sampler's set (alignset sample --list names them),
        optionally sheared to a direction (degrees)."""
        request = pb.SamplesRequest(sampler=sampler, n=int(n), seed=int(seed))
        if shear is not None:
            request.shear_deg = float(shear)
        response = self._call(self._stub.GetSamples, request, timeout)
        return _points(response.points, response.n)

    def metrics(self, timeout=None):
        """The server's counters (alignset.v1.MetricsResponse)."""
        return self._call(self._stub.GetMetrics, pb.MetricsRequest(), timeout)
