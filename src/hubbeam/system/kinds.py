"""The registration of hubbeam's kinds of part: importing a kind's module registers it
(:func:`hubbeam.system.terms.register`). A new kind of part is one module plus its line here."""

from hubbeam.system import (  # noqa: F401
    ancf_part, base_laws, controllers, drives, ffr_beams, joints, rigid_body, span_loads, tip_body)

__all__ = ["ancf_part", "base_laws", "controllers", "drives", "ffr_beams", "joints", "rigid_body", "span_loads",
           "tip_body"]
