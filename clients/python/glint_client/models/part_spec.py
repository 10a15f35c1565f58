from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from typing import cast






T = TypeVar("T", bound="PartSpec")



@_attrs_define
class PartSpec:
    """ A named group of an inline mesh's triangles.

        Attributes:
            name (str):  Example: panel.
            triangles (list[int]): Indices into `triangles`.
     """

    name: str
    triangles: list[int]





    def to_dict(self) -> dict[str, Any]:
        name = self.name

        triangles = self.triangles




        field_dict: dict[str, Any] = {}

        field_dict.update({
            "name": name,
            "triangles": triangles,
        })

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        name = d.pop("name")

        triangles = cast(list[int], d.pop("triangles"))


        part_spec = cls(
            name=name,
            triangles=triangles,
        )

        return part_spec

