from http import HTTPStatus
from typing import Any, cast
from urllib.parse import quote

import httpx

from ...client import AuthenticatedClient, Client
from ...types import Response, UNSET
from ... import errors

from ...models.error_body import ErrorBody
from ...models.light_curve import LightCurve
from ...models.request import Request
from typing import cast



def _get_kwargs(
    *,
    body: Request,

) -> dict[str, Any]:
    headers: dict[str, Any] = {}


    

    

    _kwargs: dict[str, Any] = {
        "method": "post",
        "url": "/v1/lightcurves",
    }

    _kwargs["json"] = body.to_dict()

    headers["Content-Type"] = "application/json"

    _kwargs["headers"] = headers
    return _kwargs



def _parse_response(*, client: AuthenticatedClient | Client, response: httpx.Response) -> ErrorBody | LightCurve | None:
    if response.status_code == 200:
        response_200 = LightCurve.from_dict(response.json())



        return response_200

    if response.status_code == 400:
        response_400 = ErrorBody.from_dict(response.json())



        return response_400

    if response.status_code == 401:
        response_401 = ErrorBody.from_dict(response.json())



        return response_401

    if response.status_code == 413:
        response_413 = ErrorBody.from_dict(response.json())



        return response_413

    if response.status_code == 415:
        response_415 = ErrorBody.from_dict(response.json())



        return response_415

    if response.status_code == 422:
        response_422 = ErrorBody.from_dict(response.json())



        return response_422

    if response.status_code == 503:
        response_503 = ErrorBody.from_dict(response.json())



        return response_503

    if client.raise_on_unexpected_status:
        raise errors.UnexpectedStatus(response.status_code, response.content)
    else:
        return None


def _build_response(*, client: AuthenticatedClient | Client, response: httpx.Response) -> Response[ErrorBody | LightCurve]:
    return Response(
        status_code=HTTPStatus(response.status_code),
        content=response.content,
        headers=response.headers,
        parsed=_parse_response(client=client, response=response),
    )


def sync_detailed(
    *,
    client: AuthenticatedClient | Client,
    body: Request,

) -> Response[ErrorBody | LightCurve]:
    """ Compute a light curve now.

     For requests within the synchronous limits (epochs, triangles, body size); larger ones go
    to `POST /v1/jobs`. Answers CSV when `Accept` names `text/csv`.

    Args:
        body (Request): A light-curve request: one object, its epochs, and how it is lit.

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        Response[ErrorBody | LightCurve]
     """


    kwargs = _get_kwargs(
        body=body,

    )

    response = client.get_httpx_client().request(
        **kwargs,
    )

    return _build_response(client=client, response=response)

def sync(
    *,
    client: AuthenticatedClient | Client,
    body: Request,

) -> ErrorBody | LightCurve | None:
    """ Compute a light curve now.

     For requests within the synchronous limits (epochs, triangles, body size); larger ones go
    to `POST /v1/jobs`. Answers CSV when `Accept` names `text/csv`.

    Args:
        body (Request): A light-curve request: one object, its epochs, and how it is lit.

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        ErrorBody | LightCurve
     """


    return sync_detailed(
        client=client,
body=body,

    ).parsed

async def asyncio_detailed(
    *,
    client: AuthenticatedClient | Client,
    body: Request,

) -> Response[ErrorBody | LightCurve]:
    """ Compute a light curve now.

     For requests within the synchronous limits (epochs, triangles, body size); larger ones go
    to `POST /v1/jobs`. Answers CSV when `Accept` names `text/csv`.

    Args:
        body (Request): A light-curve request: one object, its epochs, and how it is lit.

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        Response[ErrorBody | LightCurve]
     """


    kwargs = _get_kwargs(
        body=body,

    )

    response = await client.get_async_httpx_client().request(
        **kwargs
    )

    return _build_response(client=client, response=response)

async def asyncio(
    *,
    client: AuthenticatedClient | Client,
    body: Request,

) -> ErrorBody | LightCurve | None:
    """ Compute a light curve now.

     For requests within the synchronous limits (epochs, triangles, body size); larger ones go
    to `POST /v1/jobs`. Answers CSV when `Accept` names `text/csv`.

    Args:
        body (Request): A light-curve request: one object, its epochs, and how it is lit.

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        ErrorBody | LightCurve
     """


    return (await asyncio_detailed(
        client=client,
body=body,

    )).parsed
