"""Which runs the reproduction needs, as bundled scenarios with overrides."""

from __future__ import annotations

from dataclasses import dataclass, field

from hubbeam.studies.variants import FORMULATIONS as STUDY_FORMULATIONS

#: Table 6's drive speeds omega_s (rad/s)
TABLE6_SPEEDS = (0.5, 1.0, 1.5, 2.0, 2.5, 3.05)


#: modes kept by the modal FFR column
MODAL_MODES = 4

#: the formulations of the tables -> the scenario overrides that make each: the studies' three (the
#: paper's ANCF and FFR, and FFR with geometric stiffening, "ffr+") and that stiffened FFR reduced to
#: its MODAL_MODES lowest clamped-free modes ("ffr-modal"; with the stiffening its basis also keeps
#: the nodal axial coordinates, docs/ffr.md)
FORMULATIONS = {**STUDY_FORMULATIONS, "ffr-modal": STUDY_FORMULATIONS["ffr+"] + [f"beams[*].modes={MODAL_MODES}"]}


def mesh_of(formulation: str) -> str:
    """The formulation whose meshes a formulation uses ("ancf" or "ffr": modal FFR reduces the nodal one)."""
    return "ancf" if formulation == "ancf" else "ffr"


@dataclass(frozen=True)
class Case:
    """One run: a bundled scenario, the formulation (a key of FORMULATIONS), the mesh and further
    overrides."""

    example: str
    formulation: str
    elements: int
    extra: tuple[str, ...] = ()

    @property
    def key(self) -> str:
        return "/".join([self.example, self.formulation, str(self.elements), *self.extra])

    def overrides(self) -> list[str]:
        return list(FORMULATIONS[self.formulation]) + [f"beam.elements={self.elements}"] + list(self.extra)


@dataclass
class Plan:
    """The meshes per table, simulated times and steps. ``exp1_time`` and ``exp2_time`` (s)
    shorten the runs for tests; ``exp2_dt`` is the step of experiment 2 (its response is
    quasi-static: 5 ms changes the 80 s tip deflection by 2.5e-5 relative to 2 ms)."""

    table2: dict = field(default_factory=lambda: {"ancf": (4, 5, 6), "ffr": (5, 6, 7)})
    table5: dict = field(default_factory=lambda: {"ancf": (2, 4, 6, 8), "ffr": (3, 5, 7, 9)})
    fine: dict = field(default_factory=lambda: {"ancf": 6, "ffr": 7})  # Tables 3 and 6, figures
    speeds: tuple = TABLE6_SPEEDS
    exp1_time: float = 20.0
    exp2_time: float = 80.0
    exp2_dt: float | None = None  # None: the scenario's own (2 ms)

    @classmethod
    def full(cls) -> "Plan":
        return cls()

    @classmethod
    def quick(cls) -> "Plan":
        return cls(exp2_dt=5e-3)

    def _exp1(self, example, form, n):
        extra = (f"analysis.t_end={self.exp1_time}",)
        return Case(example, form, n, extra)

    def _exp2(self, form, n, omega=None):
        extra = [f"analysis.t_end={self.exp2_time}"]
        if self.exp2_dt is not None:
            extra.append(f"analysis.dt={self.exp2_dt}")
        if omega is not None:
            extra.append(f"hub.drive.omega_s={omega}")
        return Case("exp2", form, n, tuple(extra))

    def table2_cases(self):
        cases = {(form, n): self._exp1("exp1", form, n) for form, meshes in self.table2.items() for n in meshes}
        cases["ffr-modal", self.fine["ffr"]] = self._exp1("exp1", "ffr-modal", self.fine["ffr"])
        return cases

    def table3_cases(self):
        return {(example, form): self._exp1(example, form, self.fine[mesh_of(form)])
                for example in ("exp1_h4", "exp1", "exp1_h1") for form in ("ancf", "ffr", "ffr+", "ffr-modal")}

    def table5_cases(self):
        cases = {(form, n): self._exp2(form, n) for form, meshes in self.table5.items() for n in meshes}
        for form in ("ffr+", "ffr-modal"):
            cases[form, self.fine["ffr"]] = self._exp2(form, self.fine["ffr"])
        return cases

    def table6_cases(self):
        out = {}
        for omega in self.speeds:
            for form in ("ancf", "ffr", "ffr+", "ffr-modal"):
                out[omega, form] = self._exp2(form, self.fine[mesh_of(form)], None if omega == 3.05 else omega)
        return out

    def cases(self) -> list[Case]:
        """Every distinct run, longest first (a better schedule on few cores)."""
        seen = {}
        for group in (self.table5_cases(), self.table6_cases(), self.table2_cases(), self.table3_cases()):
            for case in group.values():
                seen.setdefault(case.key, case)
        return list(seen.values())
