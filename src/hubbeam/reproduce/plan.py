"""Which runs the reproduction needs, as bundled scenarios with overrides."""

from __future__ import annotations

from dataclasses import dataclass, field

#: Table 6's drive speeds omega_s (rad/s)
TABLE6_SPEEDS = (0.5, 1.0, 1.5, 2.0, 2.5, 3.05)


@dataclass(frozen=True)
class Case:
    """One run: a bundled scenario, the formulation, the mesh and further overrides."""

    example: str
    formulation: str  # "ancf" | "ffr" | "ffr+" (FFR with geometric stiffening)
    elements: int
    extra: tuple[str, ...] = ()

    @property
    def key(self) -> str:
        return "/".join([self.example, self.formulation, str(self.elements), *self.extra])

    def overrides(self) -> list[str]:
        form = "ffr" if self.formulation.startswith("ffr") else "ancf"
        out = [f'beam.formulation="{form}"', f"beam.elements={self.elements}"]
        if self.formulation == "ffr+":
            out.append("beam.geometric_stiffening=true")
        return out + list(self.extra)


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
        return {(form, n): self._exp1("exp1", form, n) for form, meshes in self.table2.items() for n in meshes}

    def table3_cases(self):
        return {(example, form): self._exp1(example, form, self.fine[form])
                for example in ("exp1_h4", "exp1", "exp1_h1") for form in ("ancf", "ffr")}

    def table5_cases(self):
        cases = {(form, n): self._exp2(form, n) for form, meshes in self.table5.items() for n in meshes}
        cases["ffr+", self.fine["ffr"]] = self._exp2("ffr+", self.fine["ffr"])
        return cases

    def table6_cases(self):
        out = {}
        for omega in self.speeds:
            for form in ("ancf", "ffr", "ffr+"):
                n = self.fine["ffr" if form.startswith("ffr") else "ancf"]
                out[omega, form] = self._exp2(form, n, None if omega == 3.05 else omega)
        return out

    def cases(self) -> list[Case]:
        """Every distinct run, longest first (a better schedule on few cores)."""
        seen = {}
        for group in (self.table5_cases(), self.table6_cases(), self.table2_cases(), self.table3_cases()):
            for case in group.values():
                seen.setdefault(case.key, case)
        return list(seen.values())
