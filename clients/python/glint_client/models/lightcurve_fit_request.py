from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..types import UNSET, Unset
from typing import cast

if TYPE_CHECKING:
  from ..models.lightcurve_fit_request_start_type_0 import LightcurveFitRequestStartType0
  from ..models.observation import Observation
  from ..models.request import Request





T = TypeVar("T", bound="LightcurveFitRequest")



@_attrs_define
class LightcurveFitRequest:
    """ The body of `POST /v1/fits/lightcurve`.

        Attributes:
            request (Request): A light-curve request: one object, its epochs, and how it is lit.
            observed (list[Observation]): The observed magnitudes; more than there are free parameters.
            free (list[str]): Free parameters by path: `materials.<name>.<parameter>` or `attitude.yaw_deg`.
            start (LightcurveFitRequestStartType0 | None | Unset): Starting values by path (default: the request's values,
                yaw 0°).
            loss (None | str | Unset): `l2` (default: weighted least squares on magnitudes), `huber` or `cauchy`.
            yaw_starts (int | None | Unset): With the yaw free: yaws screened, evenly round the circle from its start (1 to
                360;
                default 12). The three of lowest χ² are solved.
            max_evaluations (int | None | Unset): Most light curves the fit may evaluate, uncertainties included (default
                400): the
                bound the job's `percent` counts against.
     """

    request: Request
    observed: list[Observation]
    free: list[str]
    start: LightcurveFitRequestStartType0 | None | Unset = UNSET
    loss: None | str | Unset = UNSET
    yaw_starts: int | None | Unset = UNSET
    max_evaluations: int | None | Unset = UNSET





    def to_dict(self) -> dict[str, Any]:
        from ..models.lightcurve_fit_request_start_type_0 import LightcurveFitRequestStartType0 # noqa: PLC0415
        from ..models.observation import Observation # noqa: PLC0415
        from ..models.request import Request # noqa: PLC0415
        request = self.request.to_dict()

        observed = []
        for observed_item_data in self.observed:
            observed_item = observed_item_data.to_dict()
            observed.append(observed_item)



        free = self.free



        start: dict[str, Any] | None | Unset
        if isinstance(self.start, Unset):
            start = UNSET
        elif isinstance(self.start, LightcurveFitRequestStartType0):
            start = self.start.to_dict()
        else:
            start = self.start

        loss: None | str | Unset
        if isinstance(self.loss, Unset):
            loss = UNSET
        else:
            loss = self.loss

        yaw_starts: int | None | Unset
        if isinstance(self.yaw_starts, Unset):
            yaw_starts = UNSET
        else:
            yaw_starts = self.yaw_starts

        max_evaluations: int | None | Unset
        if isinstance(self.max_evaluations, Unset):
            max_evaluations = UNSET
        else:
            max_evaluations = self.max_evaluations


        field_dict: dict[str, Any] = {}

        field_dict.update({
            "request": request,
            "observed": observed,
            "free": free,
        })
        if start is not UNSET:
            field_dict["start"] = start
        if loss is not UNSET:
            field_dict["loss"] = loss
        if yaw_starts is not UNSET:
            field_dict["yaw_starts"] = yaw_starts
        if max_evaluations is not UNSET:
            field_dict["max_evaluations"] = max_evaluations

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        from ..models.lightcurve_fit_request_start_type_0 import LightcurveFitRequestStartType0 # noqa: PLC0415
        from ..models.observation import Observation # noqa: PLC0415
        from ..models.request import Request # noqa: PLC0415
        d = dict(src_dict)
        request = Request.from_dict(d.pop("request"))




        observed = []
        _observed = d.pop("observed")
        for observed_item_data in (_observed):
            observed_item = Observation.from_dict(observed_item_data)



            observed.append(observed_item)


        free = cast(list[str], d.pop("free"))


        def _parse_start(data: object) -> LightcurveFitRequestStartType0 | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            try:
                if not isinstance(data, dict):
                    raise TypeError()
                start_type_0 = LightcurveFitRequestStartType0.from_dict(data)



                return start_type_0
            except (TypeError, ValueError, AttributeError, KeyError):
                pass
            return cast(LightcurveFitRequestStartType0 | None | Unset, data)

        start = _parse_start(d.pop("start", UNSET))


        def _parse_loss(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        loss = _parse_loss(d.pop("loss", UNSET))


        def _parse_yaw_starts(data: object) -> int | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(int | None | Unset, data)

        yaw_starts = _parse_yaw_starts(d.pop("yaw_starts", UNSET))


        def _parse_max_evaluations(data: object) -> int | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(int | None | Unset, data)

        max_evaluations = _parse_max_evaluations(d.pop("max_evaluations", UNSET))


        lightcurve_fit_request = cls(
            request=request,
            observed=observed,
            free=free,
            start=start,
            loss=loss,
            yaw_starts=yaw_starts,
            max_evaluations=max_evaluations,
        )

        return lightcurve_fit_request

