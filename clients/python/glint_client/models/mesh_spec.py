from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.part_spec import PartSpec





T = TypeVar("T", bound="MeshSpec")



@_attrs_define
class MeshSpec:
    """ A mesh: inline `vertices` + `triangles`, or `obj` text, or a `builtin` name.
    Exactly one of the three forms must be given.

        Attributes:
            vertices (list[list[float]] | None | Unset): Vertex positions in metres, body frame.
            triangles (list[list[int]] | None | Unset): Vertex indices per triangle, counter-clockwise seen from outside.
            material_ids (list[int] | None | Unset): Index into `object.materials` per triangle; when absent all use
                `materials[0]`.
            obj (None | str | Unset): Wavefront OBJ text (metres); faces take the material named by `usemtl`.
            builtin (None | str | Unset): Name of an object shipped with glint (see `GET /v1/scenes`), e.g. `box-wing`.
            detail (None | str | Unset): Tessellation of a `builtin` object: `coarse` (about 2k triangles), `medium` (about
                20k) or `fine` (about 200k). Default: `medium`, except `box-wing`, `sphere` and
                `plate`, which default to their original meshes (coarse: 268, 1280 and 2 triangles;
                the box-wing's medium is the 15.5k-triangle fine-dish box-wing). Example: medium.
            parts (list[PartSpec] | None | Unset): Inline meshes only: named groups of triangles, for `articulation` (OBJ
                text names
                its groups with `g` or `o`). A triangle belongs to one part at most.
     """

    vertices: list[list[float]] | None | Unset = UNSET
    triangles: list[list[int]] | None | Unset = UNSET
    material_ids: list[int] | None | Unset = UNSET
    obj: None | str | Unset = UNSET
    builtin: None | str | Unset = UNSET
    detail: None | str | Unset = UNSET
    parts: list[PartSpec] | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        from ..models.part_spec import PartSpec # noqa: PLC0415
        vertices: list[list[float]] | None | Unset
        if isinstance(self.vertices, Unset):
            vertices = UNSET
        elif isinstance(self.vertices, list):
            vertices = []
            for vertices_type_0_item_data in self.vertices:
                vertices_type_0_item = vertices_type_0_item_data


                vertices.append(vertices_type_0_item)


        else:
            vertices = self.vertices

        triangles: list[list[int]] | None | Unset
        if isinstance(self.triangles, Unset):
            triangles = UNSET
        elif isinstance(self.triangles, list):
            triangles = []
            for triangles_type_0_item_data in self.triangles:
                triangles_type_0_item = triangles_type_0_item_data


                triangles.append(triangles_type_0_item)


        else:
            triangles = self.triangles

        material_ids: list[int] | None | Unset
        if isinstance(self.material_ids, Unset):
            material_ids = UNSET
        elif isinstance(self.material_ids, list):
            material_ids = self.material_ids


        else:
            material_ids = self.material_ids

        obj: None | str | Unset
        if isinstance(self.obj, Unset):
            obj = UNSET
        else:
            obj = self.obj

        builtin: None | str | Unset
        if isinstance(self.builtin, Unset):
            builtin = UNSET
        else:
            builtin = self.builtin

        detail: None | str | Unset
        if isinstance(self.detail, Unset):
            detail = UNSET
        else:
            detail = self.detail

        parts: list[dict[str, Any]] | None | Unset
        if isinstance(self.parts, Unset):
            parts = UNSET
        elif isinstance(self.parts, list):
            parts = []
            for parts_type_0_item_data in self.parts:
                parts_type_0_item = parts_type_0_item_data.to_dict()
                parts.append(parts_type_0_item)


        else:
            parts = self.parts


        field_dict: dict[str, Any] = {}

        field_dict.update({
        })
        if vertices is not UNSET:
            field_dict["vertices"] = vertices
        if triangles is not UNSET:
            field_dict["triangles"] = triangles
        if material_ids is not UNSET:
            field_dict["material_ids"] = material_ids
        if obj is not UNSET:
            field_dict["obj"] = obj
        if builtin is not UNSET:
            field_dict["builtin"] = builtin
        if detail is not UNSET:
            field_dict["detail"] = detail
        if parts is not UNSET:
            field_dict["parts"] = parts

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.part_spec import PartSpec # noqa: PLC0415
        d = dict(src_dict)
        def _parse_vertices(data: object) -> list[list[float]] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                vertices_type_0 = []
                _vertices_type_0 = data
                for vertices_type_0_item_data in (_vertices_type_0):
                    vertices_type_0_item = cast(list[float], vertices_type_0_item_data)

                    vertices_type_0.append(vertices_type_0_item)

                return vertices_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[list[float]] | None | Unset, data)

        vertices = _parse_vertices(d.pop("vertices", UNSET))


        def _parse_triangles(data: object) -> list[list[int]] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                triangles_type_0 = []
                _triangles_type_0 = data
                for triangles_type_0_item_data in (_triangles_type_0):
                    triangles_type_0_item = cast(list[int], triangles_type_0_item_data)

                    triangles_type_0.append(triangles_type_0_item)

                return triangles_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[list[int]] | None | Unset, data)

        triangles = _parse_triangles(d.pop("triangles", UNSET))


        def _parse_material_ids(data: object) -> list[int] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                material_ids_type_0 = cast(list[int], data)

                return material_ids_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[int] | None | Unset, data)

        material_ids = _parse_material_ids(d.pop("material_ids", UNSET))


        def _parse_obj(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        obj = _parse_obj(d.pop("obj", UNSET))


        def _parse_builtin(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        builtin = _parse_builtin(d.pop("builtin", UNSET))


        def _parse_detail(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        detail = _parse_detail(d.pop("detail", UNSET))


        def _parse_parts(data: object) -> list[PartSpec] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                parts_type_0 = []
                _parts_type_0 = data
                for parts_type_0_item_data in (_parts_type_0):
                    parts_type_0_item = PartSpec.from_dict(parts_type_0_item_data)



                    parts_type_0.append(parts_type_0_item)

                return parts_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[PartSpec] | None | Unset, data)

        parts = _parse_parts(d.pop("parts", UNSET))


        mesh_spec = cls(
            vertices=vertices,
            triangles=triangles,
            material_ids=material_ids,
            obj=obj,
            builtin=builtin,
            detail=detail,
            parts=parts,
        )

        return mesh_spec

