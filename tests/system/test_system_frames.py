"""The system's frames (hubbeam.system.system_frames): chains equal once merged share one row."""

from __future__ import annotations

import numpy as np

from hubbeam import api
from hubbeam.io.scenario import load_example
from hubbeam.system import chains as ch
from hubbeam.system.frames import chain_pose
from hubbeam.system.system_frames import HUB_AXIS


def test_an_identity_link_is_left_out_of_the_merged_chain():
    """Chain.merged drops a merged constant that is exactly the identity (a -0.0 in it is still
    the identity), keeps any other, and keeps one identity before an FFR tip (never first)."""
    minus_zero = ((1.0, -0.0, 0.0), (0.0, 1.0, -0.0), (0.0, 0.0, 1.0))
    turn = ch.revolute(0, (0.0, 1.0, 0.0), -1.0)
    chain = ch.Chain((ch.constant(), turn, ch.constant(rotation=minus_zero), ch.constant()))
    assert chain.merged().links == (turn,)
    moved = ch.Chain((turn, ch.constant((1e-300, 0.0, 0.0))))
    assert len(moved.merged().links) == 2
    rows = np.vstack([np.zeros((3, 2)), np.ones((3, 2))])
    tip = ch.ffr_tip(1, 2.0, rows[:3], rows[3:])
    assert ch.Chain((ch.constant(), tip)).merged().links == (ch.constant(), tip)


def _role_chains(system):
    """Every frame's chain built here from the parts (not read from system.frames), by role."""
    layout = system.layout
    base = system.base.chain(layout.base_x.start)
    shaft = base.then(system.placement.link())
    hub = shaft.then(ch.revolute(layout.theta, HUB_AXIS, -1.0))
    roles = {"base": (system.frames.base, base), "shaft": (system.frames.shaft, shaft), "hub": (system.frames.hub, hub)}
    for k, part in enumerate(system.beams):
        mount = part.mount
        axis = hub.then(mount.axis_link())
        roles[f"reference {k}"] = (system.frames.reference(k), hub.then(mount.reference_link()))
        roles[f"joint {k}"] = (system.frames.joint(k), axis)
        roles[f"root {k}"] = (system.frames.root(k), axis.then(*mount.joint_links(layout.joint_x(k).start),
                                                                   mount.twist_link()))
    body = next(b for b in system.rigid_bodies if b.name == "base")
    roles["base body"] = (body.chain, base.then(ch.constant(system.base.centre_of_mass)))
    return roles


def test_frames_equal_once_merged_share_a_row_and_each_keeps_its_pose():
    """spacecraft3d (a free bus, its hub on the bus's origin and axes, panels at azimuth 0 and
    180 without twist, the bus's centre of mass at its origin): the base, the shaft and the
    bus's body share one row, the hub and panel 0's reference another, each panel's joint and
    root frames one; every frame's pose, Jacobians and their derivatives in the system's table
    are those of its own chain evaluated alone, at a state away from rest."""
    system = api.build_system(load_example("spacecraft3d", ['beams[*].formulation="ffr"', 'beams[*].modes=4']))
    roles = _role_chains(system)
    table = system.frames.table
    assert table.orders.shape[0] == 5 < len(roles)
    assert len({roles[r][0] for r in ("base", "shaft", "base body")}) == 1
    assert roles["hub"][0] == roles["reference 0"][0] != roles["reference 1"][0]
    rng = np.random.default_rng(24)
    x = rng.normal(size=system.layout.nx)
    for name, (index, chain) in roles.items():
        shared = chain_pose(table, index, x, order=2)
        alone = chain_pose(ch.ChainTable.of([chain]), 0, x, order=2)
        for got, want in zip(shared, alone):
            np.testing.assert_array_equal(got, want, err_msg=name)
