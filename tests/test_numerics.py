"""The shared numerical helpers (hubbeam.numerics)."""

import numpy as np

from hubbeam.numerics import coupled_groups


def test_coupled_groups_are_the_blocks_of_a_shuffled_block_diagonal_pattern():
    """Blocks of known sizes, coordinates shuffled, couplings in one triangle only (an entry
    links both ways) and one block coupled through a chain, not directly: the groups are the
    blocks, each ascending, in the order of their first coordinate."""
    rng = np.random.default_rng(3)
    sizes = [3, 1, 4, 2]
    place = rng.permutation(sum(sizes))
    blocks, start = [], 0
    for size in sizes:
        blocks.append(np.sort(place[start:start + size]))
        start += size
    pattern = np.zeros((10, 10), dtype=bool)
    for b in blocks:
        for i, j in zip(b[:-1], b[1:]):  # a chain: b[0] and b[-1] coupled only through the others
            pattern[max(i, j), min(i, j)] = True
    groups = coupled_groups(pattern)
    expected = sorted(blocks, key=lambda b: b[0])
    assert len(groups) == len(expected)
    for g, b in zip(groups, expected):
        assert np.array_equal(g, b)
    assert coupled_groups(np.zeros((0, 0), dtype=bool)) == []
