from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.material_albedo import MaterialAlbedo





T = TypeVar("T", bound="Summary")



@_attrs_define
class Summary:
    """ How the light curve was computed.

        Attributes:
            epochs (int):
            triangles (int):
            faces (int): Planar faces after merging coplanar connected triangles of one material.
            rays (int): Shadow and occlusion rays cast over all epochs.
            elapsed_ms (float): Wall-clock time of the computation, ms.
            method (str): The method used and why it was chosen.
            convex (bool): Whether the mesh was detected as convex (no rays needed).
            materials (list[MaterialAlbedo] | Unset): Per material, in the request's order: how much of the light it
                receives it
                reflects.
     """

    epochs: int
    triangles: int
    faces: int
    rays: int
    elapsed_ms: float
    method: str
    convex: bool
    materials: list[MaterialAlbedo] | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.material_albedo import MaterialAlbedo # noqa: PLC0415
        epochs = self.epochs

        triangles = self.triangles

        faces = self.faces

        rays = self.rays

        elapsed_ms = self.elapsed_ms

        method = self.method

        convex = self.convex

        materials: list[dict[str, Any]] | Unset = UNSET
        if not isinstance(self.materials, Unset):
            materials = []
            for materials_item_data in self.materials:
                materials_item = materials_item_data.to_dict()
                materials.append(materials_item)




        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "epochs": epochs,
            "triangles": triangles,
            "faces": faces,
            "rays": rays,
            "elapsed_ms": elapsed_ms,
            "method": method,
            "convex": convex,
        })
        if materials is not UNSET:
            field_dict["materials"] = materials

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.material_albedo import MaterialAlbedo # noqa: PLC0415
        d = dict(src_dict)
        epochs = d.pop("epochs")

        triangles = d.pop("triangles")

        faces = d.pop("faces")

        rays = d.pop("rays")

        elapsed_ms = d.pop("elapsed_ms")

        method = d.pop("method")

        convex = d.pop("convex")

        _materials = d.pop("materials", UNSET)
        materials: list[MaterialAlbedo] | Unset = UNSET
        if _materials is not UNSET:
            materials = []
            for materials_item_data in _materials:
                materials_item = MaterialAlbedo.from_dict(materials_item_data)



                materials.append(materials_item)


        summary = cls(
            epochs=epochs,
            triangles=triangles,
            faces=faces,
            rays=rays,
            elapsed_ms=elapsed_ms,
            method=method,
            convex=convex,
            materials=materials,
        )


        summary.additional_properties = d
        return summary

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
