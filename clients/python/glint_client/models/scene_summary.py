from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="SceneSummary")



@_attrs_define
class SceneSummary:
    """ A built-in object and its example request.

        Attributes:
            name (str): Name, for `{"mesh": {"builtin": name}}` and `GET /v1/scenes/{name}`.
            description (str): What the object is (sizes in metres).
            triangles (int): Triangles in the mesh at its default detail (0 when the scene is only an example
                request).
            materials (list[str]): Material names the mesh uses, in material-id order; a request's `materials` must
                name them.
            example_epochs (int | None | Unset): Epochs in the example request, when there is one.
            example_url (None | str | Unset): Where to fetch the example request.
     """

    name: str
    description: str
    triangles: int
    materials: list[str]
    example_epochs: int | None | Unset = UNSET
    example_url: None | str | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        name = self.name

        description = self.description

        triangles = self.triangles

        materials = self.materials



        example_epochs: int | None | Unset
        if isinstance(self.example_epochs, Unset):
            example_epochs = UNSET
        else:
            example_epochs = self.example_epochs

        example_url: None | str | Unset
        if isinstance(self.example_url, Unset):
            example_url = UNSET
        else:
            example_url = self.example_url


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "name": name,
            "description": description,
            "triangles": triangles,
            "materials": materials,
        })
        if example_epochs is not UNSET:
            field_dict["example_epochs"] = example_epochs
        if example_url is not UNSET:
            field_dict["example_url"] = example_url

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        name = d.pop("name")

        description = d.pop("description")

        triangles = d.pop("triangles")

        materials = cast(list[str], d.pop("materials"))


        def _parse_example_epochs(data: object) -> int | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(int | None | Unset, data)

        example_epochs = _parse_example_epochs(d.pop("example_epochs", UNSET))


        def _parse_example_url(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        example_url = _parse_example_url(d.pop("example_url", UNSET))


        scene_summary = cls(
            name=name,
            description=description,
            triangles=triangles,
            materials=materials,
            example_epochs=example_epochs,
            example_url=example_url,
        )


        scene_summary.additional_properties = d
        return scene_summary

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
