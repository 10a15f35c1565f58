from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.angle_sample import AngleSample





T = TypeVar("T", bound="ArticulationSpec")



@_attrs_define
class ArticulationSpec:
    """ A hinge: `parts` (names of triangle groups: an OBJ `g`/`o` group, an inline mesh's
    `parts`, or else a material name) turn about the line through `pivot` along `axis`
    (body frame, the mesh as given), right-handed, by an angle each epoch. The angle 0 is
    the mesh as given. `law`:
    - `sun-tracking`: the angle that turns `normal` (default: the part's area-weighted
      normal, its front face) onto the Sun's projection on the plane normal to the axis;
      0 when the Sun lies along the axis.
    - `fixed`: `angle_deg`.
    - `angles`: a `series` of `{ "t": ..., "angle_deg": ... }`, linear between samples,
      covering every epoch (t in ISO UTC or seconds: after `times.start` in `geometry`,
      on the epochs' own scale with explicit `epochs`).

    A hinge whose parts lie within an earlier hinge's parts is nested in it: its axis and
    pivot (given in the mesh as given) turn with that parent (two-axis tracking).

        Attributes:
            parts (list[str]):  Example: ['panel'].
            law (str):  Example: sun-tracking.
            axis (list[float]): Hinge direction, body frame (any length, not zero). Example: [0.0, 1.0, 0.0].
            pivot (list[float] | None | Unset): A point of the hinge line, m, body frame. Default [0, 0, 0].
            normal (list[float] | None | Unset): `sun-tracking`: the body-frame direction (the mesh as given) that follows
                the Sun.
            angle_deg (float | None | Unset): `fixed`: the angle, degrees (−360 to 360).
            series (list[AngleSample] | None | Unset): `angles`: the angle against time.
     """

    parts: list[str]
    law: str
    axis: list[float]
    pivot: list[float] | None | Unset = UNSET
    normal: list[float] | None | Unset = UNSET
    angle_deg: float | None | Unset = UNSET
    series: list[AngleSample] | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        from ..models.angle_sample import AngleSample # noqa: PLC0415
        parts = self.parts



        law = self.law

        axis = self.axis



        pivot: list[float] | None | Unset
        if isinstance(self.pivot, Unset):
            pivot = UNSET
        elif isinstance(self.pivot, list):
            pivot = self.pivot


        else:
            pivot = self.pivot

        normal: list[float] | None | Unset
        if isinstance(self.normal, Unset):
            normal = UNSET
        elif isinstance(self.normal, list):
            normal = self.normal


        else:
            normal = self.normal

        angle_deg: float | None | Unset
        if isinstance(self.angle_deg, Unset):
            angle_deg = UNSET
        else:
            angle_deg = self.angle_deg

        series: list[dict[str, Any]] | None | Unset
        if isinstance(self.series, Unset):
            series = UNSET
        elif isinstance(self.series, list):
            series = []
            for series_type_0_item_data in self.series:
                series_type_0_item = series_type_0_item_data.to_dict()
                series.append(series_type_0_item)


        else:
            series = self.series


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "parts": parts,
            "law": law,
            "axis": axis,
        })
        if pivot is not UNSET:
            field_dict["pivot"] = pivot
        if normal is not UNSET:
            field_dict["normal"] = normal
        if angle_deg is not UNSET:
            field_dict["angle_deg"] = angle_deg
        if series is not UNSET:
            field_dict["series"] = series

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.angle_sample import AngleSample # noqa: PLC0415
        d = dict(src_dict)
        parts = cast(list[str], d.pop("parts"))


        law = d.pop("law")

        axis = cast(list[float], d.pop("axis"))


        def _parse_pivot(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                pivot_type_0 = cast(list[float], data)

                return pivot_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        pivot = _parse_pivot(d.pop("pivot", UNSET))


        def _parse_normal(data: object) -> list[float] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                normal_type_0 = cast(list[float], data)

                return normal_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[float] | None | Unset, data)

        normal = _parse_normal(d.pop("normal", UNSET))


        def _parse_angle_deg(data: object) -> float | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(float | None | Unset, data)

        angle_deg = _parse_angle_deg(d.pop("angle_deg", UNSET))


        def _parse_series(data: object) -> list[AngleSample] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                series_type_0 = []
                _series_type_0 = data
                for series_type_0_item_data in (_series_type_0):
                    series_type_0_item = AngleSample.from_dict(series_type_0_item_data)



                    series_type_0.append(series_type_0_item)

                return series_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[AngleSample] | None | Unset, data)

        series = _parse_series(d.pop("series", UNSET))


        articulation_spec = cls(
            parts=parts,
            law=law,
            axis=axis,
            pivot=pivot,
            normal=normal,
            angle_deg=angle_deg,
            series=series,
        )

        return articulation_spec

