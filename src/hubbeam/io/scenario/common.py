"""What every table of a scenario shares: strict models, number and vector types, file paths,
and tables whose choice key decides their other keys."""

from __future__ import annotations

from pathlib import Path
from typing import Annotated, ClassVar

from pydantic import (
    BaseModel,
    ConfigDict,
    Field,
    ValidationInfo,
    field_validator,
    model_serializer,
    model_validator,
)


class StrictTable(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True, allow_inf_nan=False, frozen=True)


Positive = Annotated[float, Field(gt=0.0)]
NonNegative = Annotated[float, Field(ge=0.0)]
Vector3 = Annotated[list[float], Field(min_length=3, max_length=3)]
NonNegativeVector3 = Annotated[list[NonNegative], Field(min_length=3, max_length=3)]
Identifier = Annotated[str, Field(min_length=1, max_length=64, pattern=r"^[A-Za-z_][A-Za-z0-9_]*$")]

#: precone limit (deg): the FFR reference frame's Cardan angles become singular at 90 deg
MAX_PRECONE_DEG = 80.0
#: relative tolerance of "a whole multiple of analysis.dt"
STEP_TOLERANCE = 1e-9


def _given(model: BaseModel, own: tuple[str, ...], required: tuple[str, ...], what: str) -> None:
    """Only ``own`` keys (besides the selector) may be given and every ``required`` one must be."""
    given = model.model_fields_set
    for key in type(model).model_fields:
        if key in given and key not in own and key not in ("profile", "law"):
            raise ValueError(f"{key}: not a key of {what} (its keys: {', '.join(own)})")
    for key in required:
        if key not in given:
            raise ValueError(f"{key}: required for {what}")


def _absolute(value: str | None, info: ValidationInfo) -> str | None:
    """A table's path made absolute: relative to ``context['base_dir']`` (the scenario file's
    folder), else to the current directory."""
    if value is None:
        return None
    path = Path(value).expanduser()
    if not path.is_absolute():
        base = (info.context or {}).get("base_dir")
        path = Path(base if base is not None else Path.cwd()) / path
    return str(path.absolute())


def _check_file(path: str) -> None:
    p = Path(path)
    if not p.exists():
        raise ValueError(f"file: no such file {path}")
    if not p.is_file():
        raise ValueError(f"file: not a file {path}")




class KeyedChoice(StrictTable):
    """A table whose choice key (``profile``, ``law``) decides which of its other keys it takes
    (``_keys``: choice -> (its keys, the required ones)); the others keep their neutral defaults
    and are left out of :meth:`Scenario.to_dict`. ``file`` is stored as an absolute path and
    must exist."""

    _choice: ClassVar[str]
    _keys: ClassVar[dict[str, tuple[tuple[str, ...], tuple[str, ...]]]]

    @field_validator("file", check_fields=False)
    @classmethod
    def _absolute_file(cls, value, info: ValidationInfo):
        return _absolute(value, info)

    @model_validator(mode="after")
    def _own_keys(self):
        choice = getattr(self, self._choice)
        own, required = self._keys[choice]
        _given(self, own, required, f"{self._choice} {choice!r}")
        if self.file is not None:
            _check_file(self.file)
        return self

    @model_serializer(mode="wrap")
    def _dump(self, handler):
        return {k: v for k, v in handler(self).items() if k == self._choice or k in self.model_fields_set}



