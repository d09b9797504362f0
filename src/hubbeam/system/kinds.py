"""The registration of hubbeam's kinds of part: importing a kind's module registers it
(:func:`hubbeam.system.terms.register`). A new kind of part is one module plus its line here."""

from hubbeam.system import ancf_part, base_laws, controllers, drives, ffr_part, rigid_body, tip_body  # noqa: F401

__all__ = ["ancf_part", "base_laws", "controllers", "drives", "ffr_part", "rigid_body", "tip_body"]
