from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.epoch_result import EpochResult
  from ..models.summary import Summary
  from ..models.thumbnail import Thumbnail





T = TypeVar("T", bound="LightCurve")



@_attrs_define
class LightCurve:
    """ The light curve and how it was computed. (Named `LightCurve` in the OpenAPI spec: a
    schema called `Response` collides with the generated Python client's own `Response`.)

        Attributes:
            epochs (list[EpochResult]):
            summary (Summary): How the light curve was computed.
            thumbnails (list[Thumbnail] | None | Unset): Rendered images, when the request asked for `thumbnails`.
            warnings (list[str] | Unset): What the caller should know about the result (a material that reflects more light
                than it receives); absent when there is nothing to say.
     """

    epochs: list[EpochResult]
    summary: Summary
    thumbnails: list[Thumbnail] | None | Unset = UNSET
    warnings: list[str] | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        from ..models.epoch_result import EpochResult # noqa: PLC0415
        from ..models.summary import Summary # noqa: PLC0415
        from ..models.thumbnail import Thumbnail # noqa: PLC0415
        epochs = []
        for epochs_item_data in self.epochs:
            epochs_item = epochs_item_data.to_dict()
            epochs.append(epochs_item)



        summary = self.summary.to_dict()

        thumbnails: list[dict[str, Any]] | None | Unset
        if isinstance(self.thumbnails, Unset):
            thumbnails = UNSET
        elif isinstance(self.thumbnails, list):
            thumbnails = []
            for thumbnails_type_0_item_data in self.thumbnails:
                thumbnails_type_0_item = thumbnails_type_0_item_data.to_dict()
                thumbnails.append(thumbnails_type_0_item)


        else:
            thumbnails = self.thumbnails

        warnings: list[str] | Unset = UNSET
        if not isinstance(self.warnings, Unset):
            warnings = self.warnings




        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "epochs": epochs,
            "summary": summary,
        })
        if thumbnails is not UNSET:
            field_dict["thumbnails"] = thumbnails
        if warnings is not UNSET:
            field_dict["warnings"] = warnings

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.epoch_result import EpochResult # noqa: PLC0415
        from ..models.summary import Summary # noqa: PLC0415
        from ..models.thumbnail import Thumbnail # noqa: PLC0415
        d = dict(src_dict)
        epochs = []
        _epochs = d.pop("epochs")
        for epochs_item_data in (_epochs):
            epochs_item = EpochResult.from_dict(epochs_item_data)



            epochs.append(epochs_item)


        summary = Summary.from_dict(d.pop("summary"))




        def _parse_thumbnails(data: object) -> list[Thumbnail] | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, list):
                    raise TypeError()
                thumbnails_type_0 = []
                _thumbnails_type_0 = data
                for thumbnails_type_0_item_data in (_thumbnails_type_0):
                    thumbnails_type_0_item = Thumbnail.from_dict(thumbnails_type_0_item_data)



                    thumbnails_type_0.append(thumbnails_type_0_item)

                return thumbnails_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(list[Thumbnail] | None | Unset, data)

        thumbnails = _parse_thumbnails(d.pop("thumbnails", UNSET))


        warnings = cast(list[str], d.pop("warnings", UNSET))


        light_curve = cls(
            epochs=epochs,
            summary=summary,
            thumbnails=thumbnails,
            warnings=warnings,
        )


        light_curve.additional_properties = d
        return light_curve

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
