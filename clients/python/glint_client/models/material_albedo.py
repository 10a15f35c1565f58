from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset







T = TypeVar("T", bound="MaterialAlbedo")



@_attrs_define
class MaterialAlbedo:
    """ A material's directional-hemispherical albedo ρ(θi) = ∫ f cosθr dω over the view
    hemisphere (dimensionless): above 1 it reflects more light than it receives, as the
    paper's Eqs. 7–8 do for its own fitted materials (docs/physics.md §6.5).

        Attributes:
            name (str):
            albedo_normal (float): ρ for light at normal incidence.
            albedo_max (float): The largest ρ over incidences 0°, 30°, 50°, 65°, 75° and 85°.
            albedo_max_incidence_deg (float): The incidence of `albedo_max`, degrees.
     """

    name: str
    albedo_normal: float
    albedo_max: float
    albedo_max_incidence_deg: float
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        name = self.name

        albedo_normal = self.albedo_normal

        albedo_max = self.albedo_max

        albedo_max_incidence_deg = self.albedo_max_incidence_deg


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "name": name,
            "albedo_normal": albedo_normal,
            "albedo_max": albedo_max,
            "albedo_max_incidence_deg": albedo_max_incidence_deg,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        name = d.pop("name")

        albedo_normal = d.pop("albedo_normal")

        albedo_max = d.pop("albedo_max")

        albedo_max_incidence_deg = d.pop("albedo_max_incidence_deg")

        material_albedo = cls(
            name=name,
            albedo_normal=albedo_normal,
            albedo_max=albedo_max,
            albedo_max_incidence_deg=albedo_max_incidence_deg,
        )


        material_albedo.additional_properties = d
        return material_albedo

    @property
    def additional_keys(self) -> list[str]:
        return list(self.additional_properties.keys())

    def __getitem__(self, key: str) -> Any:
        return self.additional_properties[key]

    def __setitem__(self, key: str, value: Any) -> None:
        self.additional_properties[key] = value

    def __delitem__(self, key: str) -> None:
        del self.additional_properties[key]

    def __contains__(self, key: str) -> bool:
        return key in self.additional_properties
