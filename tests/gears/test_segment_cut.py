"""Segments passed over by the swept-teeth cut because they cannot lower a bin: the cut they leave equals cutting
every segment, for short, long and wrapping segments."""
import numpy as np

from transplanter.gears import swept_teeth


def _cut_everything(at_edge, width, perimeter, ends):
    """Each segment's height at every bin edge it crosses, one segment at a time (run taken the short way round)."""
    for s_a, h_a, s_b, h_b in ends.T:
        run = np.mod(s_b - s_a + perimeter / 2, perimeter) - perimeter / 2
        if run < 0:
            s_a, h_a, h_b, run = s_b, h_b, h_a, -run
        for edge in range(int(np.floor(s_a / width)) + 1, int(np.floor((s_a + run) / width)) + 1):
            level = h_a + (edge * width - s_a) * ((h_b - h_a) / run)
            at_edge[edge % len(at_edge)] = min(at_edge[edge % len(at_edge)], level)


def test_passing_over_segments_leaves_the_cut_of_all_of_them():
    """Bins already lowered far (the vertices' heights) but for five left at the blank's tip, then segments from a
    tenth of a bin to 3000 bins long, some across the curve's start, some whose only tip bin is their first or
    last, one over 2400 bins whose only tip bin lies far from both ends: each leaves the bins as cutting it at
    every edge it crosses does."""
    generator = np.random.default_rng(5)
    count, width = 5000, 0.01
    perimeter = count * width
    spikes = np.array([3, 700, 2500, 4200, 4998])
    reached = np.full(count, -1.0)
    reached[spikes] = 1.0
    length = width * np.exp(generator.uniform(np.log(0.1), np.log(3000), 3000))
    s_a = generator.uniform(0, perimeter, 3000)
    s_b = np.mod(s_a + generator.choice([-1, 1], 3000) * length, perimeter)
    # a bin k meets edges k and k + 1: segments that reach a tip bin only by its right edge, only by its left edge
    s_a = np.r_[s_a, (spikes + 1.5) * width, (spikes - 5.5) * width, 1400.5 * width]
    s_b = np.r_[s_b, (spikes + 9.5) * width, (spikes + 0.5) * width, 3800.5 * width]
    ends = np.stack([s_a, generator.uniform(-0.9, 0.9, len(s_a)), np.mod(s_b, perimeter),
                     generator.uniform(-0.9, 0.9, len(s_a))])
    for segment in range(ends.shape[1]):        # one at a time, so that no other segment hides one passed over
        passing, every = np.full(count, 1.0), np.full(count, 1.0)
        swept_teeth._cut(passing, reached, width, perimeter, ends[:, segment:segment + 1])
        _cut_everything(every, width, perimeter, ends[:, segment:segment + 1])
        assert np.array_equal(np.minimum(reached, np.minimum(passing, np.roll(passing, -1))),
                              np.minimum(reached, np.minimum(every, np.roll(every, -1))))
