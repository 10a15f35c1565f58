from __future__ import annotations

from collections.abc import Mapping
from typing import Any, TypeVar, BinaryIO, TextIO, TYPE_CHECKING, Generator

from attrs import define as _attrs_define
from attrs import field as _attrs_field

from ..types import UNSET, Unset

from ..models.job_kind import JobKind
from ..models.job_state import JobState
from ..types import UNSET, Unset
from typing import cast






T = TypeVar("T", bound="JobStatus")



@_attrs_define
class JobStatus:
    """ A job's status as `GET /v1/jobs/{id}` reports it.

        Attributes:
            id (str): Job id (UUID).
            state (JobState): Where a job is in its life.
            kind (JobKind): What a job computes.
            percent (float): How far it has come, 0–100: epochs computed of the total; for a fit, light curves
                evaluated of `evaluations_max` (100 once done).
            epochs_done (int): Epochs computed so far (a fit: over all its light curves).
            epochs_total (int): Epochs in the request; for a fit, the observed epochs times `evaluations_max`, the
                most it may compute.
            created_at (str): When the job was accepted (RFC 3339, UTC).
            attempts (int): Times the job was started (above 1 when a restart interrupted it).
            evaluations_done (int | None | Unset): A fit: light curves evaluated so far (its result's `solver.evaluations`
                once done).
            evaluations_max (int | None | Unset): A fit: the most light curves it may evaluate (its `max_evaluations`).
            started_at (None | str | Unset): When the current run started (RFC 3339, UTC).
            finished_at (None | str | Unset): When the job reached its final state (RFC 3339, UTC).
            expires_at (None | str | Unset): When a finished job and its result will be removed (RFC 3339, UTC).
            error (None | str | Unset): Why the job failed.
            result_url (None | str | Unset): Where to fetch the result once `state` is `done`.
     """

    id: str
    state: JobState
    kind: JobKind
    percent: float
    epochs_done: int
    epochs_total: int
    created_at: str
    attempts: int
    evaluations_done: int | None | Unset = UNSET
    evaluations_max: int | None | Unset = UNSET
    started_at: None | str | Unset = UNSET
    finished_at: None | str | Unset = UNSET
    expires_at: None | str | Unset = UNSET
    error: None | str | Unset = UNSET
    result_url: None | str | Unset = UNSET
    additional_properties: dict[str, Any] = _attrs_field(init=False, factory=dict)





    def to_dict(self) -> dict[str, Any]:
        id = self.id

        state = self.state.value

        kind = self.kind.value

        percent = self.percent

        epochs_done = self.epochs_done

        epochs_total = self.epochs_total

        created_at = self.created_at

        attempts = self.attempts

        evaluations_done: int | None | Unset
        if isinstance(self.evaluations_done, Unset):
            evaluations_done = UNSET
        else:
            evaluations_done = self.evaluations_done

        evaluations_max: int | None | Unset
        if isinstance(self.evaluations_max, Unset):
            evaluations_max = UNSET
        else:
            evaluations_max = self.evaluations_max

        started_at: None | str | Unset
        if isinstance(self.started_at, Unset):
            started_at = UNSET
        else:
            started_at = self.started_at

        finished_at: None | str | Unset
        if isinstance(self.finished_at, Unset):
            finished_at = UNSET
        else:
            finished_at = self.finished_at

        expires_at: None | str | Unset
        if isinstance(self.expires_at, Unset):
            expires_at = UNSET
        else:
            expires_at = self.expires_at

        error: None | str | Unset
        if isinstance(self.error, Unset):
            error = UNSET
        else:
            error = self.error

        result_url: None | str | Unset
        if isinstance(self.result_url, Unset):
            result_url = UNSET
        else:
            result_url = self.result_url


        field_dict: dict[str, Any] = {}
        field_dict.update(self.additional_properties)
        field_dict.update({
            "id": id,
            "state": state,
            "kind": kind,
            "percent": percent,
            "epochs_done": epochs_done,
            "epochs_total": epochs_total,
            "created_at": created_at,
            "attempts": attempts,
        })
        if evaluations_done is not UNSET:
            field_dict["evaluations_done"] = evaluations_done
        if evaluations_max is not UNSET:
            field_dict["evaluations_max"] = evaluations_max
        if started_at is not UNSET:
            field_dict["started_at"] = started_at
        if finished_at is not UNSET:
            field_dict["finished_at"] = finished_at
        if expires_at is not UNSET:
            field_dict["expires_at"] = expires_at
        if error is not UNSET:
            field_dict["error"] = error
        if result_url is not UNSET:
            field_dict["result_url"] = result_url

        return field_dict



    @classmethod
    def from_dict(cls: type[T], src_dict: Mapping[str, Any]) -> T:
        d = dict(src_dict)
        id = d.pop("id")

        state = JobState(d.pop("state"))




        kind = JobKind(d.pop("kind"))




        percent = d.pop("percent")

        epochs_done = d.pop("epochs_done")

        epochs_total = d.pop("epochs_total")

        created_at = d.pop("created_at")

        attempts = d.pop("attempts")

        def _parse_evaluations_done(data: object) -> int | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(int | None | Unset, data)

        evaluations_done = _parse_evaluations_done(d.pop("evaluations_done", UNSET))


        def _parse_evaluations_max(data: object) -> int | None | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(int | None | Unset, data)

        evaluations_max = _parse_evaluations_max(d.pop("evaluations_max", UNSET))


        def _parse_started_at(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        started_at = _parse_started_at(d.pop("started_at", UNSET))


        def _parse_finished_at(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        finished_at = _parse_finished_at(d.pop("finished_at", UNSET))


        def _parse_expires_at(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        expires_at = _parse_expires_at(d.pop("expires_at", UNSET))


        def _parse_error(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        error = _parse_error(d.pop("error", UNSET))


        def _parse_result_url(data: object) -> None | str | Unset:
            if data is None:
                return data
            if isinstance(data, Unset):
                return data
            return cast(None | str | Unset, data)

        result_url = _parse_result_url(d.pop("result_url", UNSET))


        job_status = cls(
            id=id,
            state=state,
            kind=kind,
            percent=percent,
            epochs_done=epochs_done,
            epochs_total=epochs_total,
            created_at=created_at,
            attempts=attempts,
            evaluations_done=evaluations_done,
            evaluations_max=evaluations_max,
            started_at=started_at,
            finished_at=finished_at,
            expires_at=expires_at,
            error=error,
            result_url=result_url,
        )


        job_status.additional_properties = d
        return job_status

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
