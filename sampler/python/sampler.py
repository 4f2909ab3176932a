"""The sampler library for a renderer prototyped in NumPy: a table file
exported from a server's cache (`alignset export`), and the per-pixel recipe
of alignset's rendered gains, with no server at render time. The same four
calls as the C++ library (<alignset/aligned_sampler.h>, docs/sampler.md):

    from alignset.sampler import AlignedSampler, SetTable, block_of
    table = SetTable.load("sets.tbl")
    s = AlignedSampler(table, n=256, image_width=W)          # construction "lattice"
    pre = {}                                                 # (x, y) -> M values
    for (x, y) in pixels:
        pts = s.prepass_points(x, y)                         # (M, 2) in [0, 1)^2
        pre[x, y] = f(x + pts[:, 0], y + pts[:, 1])
    for (x, y) in pixels:
        plan = s.plan(x, y, block_of(pre, x, y, s.block_radius))
        pts = s.main_points(plan)                            # (N, 2)
        image[y, x] = s.estimate(plan, pre[x, y], f(x + pts[:, 0], y + pts[:, 1]))

Refusals raise ValueError (bad input), KeyError (a size, construction or
file the table does not have) or RuntimeError (a damaged table file).
"""

from alignset._sampler import AlignedSampler, PixelPlan, SetTable

__all__ = ["AlignedSampler", "PixelPlan", "SetTable", "block_of"]


def block_of(prepass, x, y, radius):
    """The block a plan reads: the (2 radius + 1)^2 pixels around (x, y), row
    by row from (x - radius, y - radius), each its pre-pass values from the
    mapping `prepass` ((x, y) -> values), None for a pixel it does not hold
    (outside the image)."""
    side = 2 * radius + 1
    return [prepass.get((x + k % side - radius, y + k // side - radius)) for k in range(side * side)]
