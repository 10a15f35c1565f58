from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast

if TYPE_CHECKING:
  from ..models.material_object import MaterialObject
  from ..models.mesh_spec import MeshSpec





T = TypeVar("T", bound="ObjectSpec")



@_attrs_define
class ObjectSpec:
    """ The object: a triangle mesh and the materials its triangles use.

        Attributes:
            mesh (MeshSpec): A mesh: inline `vertices` + `triangles`, or `obj` text, or a `builtin` name.
                Exactly one of the three forms must be given.
            materials (list[MaterialObject | str]): Materials, indexed by `mesh.material_ids` (inline meshes) or matched by
                name
                (`usemtl` in OBJ text and built-in objects). A bare string names a preset.
     """

    mesh: MeshSpec
    materials: list[MaterialObject | str]





    def to_dict(self) -> dict[str, Any]:
        from ..models.material_object import MaterialObject # noqa: PLC0415
        from ..models.mesh_spec import MeshSpec # noqa: PLC0415
        mesh = self.mesh.to_dict()

        materials = []
        for materials_item_data in self.materials:
            materials_item: dict[str, Any] | str
            if isinstance(materials_item_data, MaterialObject):
                materials_item = materials_item_data.to_dict()
            else:
                materials_item = materials_item_data
            materials.append(materials_item)




        field_dict: dict[str, Any] = {}

        field_dict.update({
            "mesh": mesh,
            "materials": materials,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.material_object import MaterialObject # noqa: PLC0415
        from ..models.mesh_spec import MeshSpec # noqa: PLC0415
        d = dict(src_dict)
        mesh = MeshSpec.from_dict(d.pop("mesh"))




        materials = []
        _materials = d.pop("materials")
        for materials_item_data in (_materials):
            def _parse_materials_item(data: object) -> MaterialObject | str:
                try:
                    if not isinstance(data, dict):
                        raise TypeError()
                    componentsschemas_material_spec_type_1 = MaterialObject.from_dict(data)



                    return componentsschemas_material_spec_type_1
                except (TypeError, ValueError, AttributeError, KeyError):
                    pass
                return cast(MaterialObject | str, data)

            materials_item = _parse_materials_item(materials_item_data)

            materials.append(materials_item)


        object_spec = cls(
            mesh=mesh,
            materials=materials,
        )

        return object_spec

