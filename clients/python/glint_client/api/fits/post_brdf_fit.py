from http import HTTPStatus
from typing import Any, cast
from urllib.parse import quote

import httpx

from ...client import AuthenticatedClient, Client
from ...types import Response, UNSET
from ... import errors

from ...models.brdf_fit import BrdfFit
from ...models.brdf_fit_request import BrdfFitRequest
from ...models.error_body import ErrorBody
from typing import cast



def _get_kwargs(
    *,
    body: BrdfFitRequest,

) -> dict[str, Any]:
    headers: dict[str, Any] = {}


    

    

    _kwargs: dict[str, Any] = {
        "method": "post",
        "url": "/v1/fits/brdf",
    }

    _kwargs["json"] = body.to_dict()

    headers["Content-Type"] = "application/json"

    _kwargs["headers"] = headers
    return _kwargs



def _parse_response(*, client: AuthenticatedClient | Client, response: httpx.Response) -> BrdfFit | ErrorBody | None:
    if response.status_code == 200:
        response_200 = BrdfFit.from_dict(response.json())



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


def _build_response(*, client: AuthenticatedClient | Client, response: httpx.Response) -> Response[BrdfFit | ErrorBody]:
    return Response(
        status_code=HTTPStatus(response.status_code),
        content=response.content,
        headers=response.headers,
        parsed=_parse_response(client=client, response=response),
    )


def sync_detailed(
    *,
    client: AuthenticatedClient | Client,
    body: BrdfFitRequest,

) -> Response[BrdfFit | ErrorBody]:
    """ Fit a material model to measured BRDF samples.

     What `glint fit-brdf` does with a CSV file: bounded, robust (Huber by default)
    Levenberg–Marquardt from several starts; the parameters come back under the names a
    request's material takes, with 1σ uncertainties from the Jacobian at the optimum.

    Args:
        body (BrdfFitRequest): The body of `POST /v1/fits/brdf`: what `glint fit-brdf` takes as a
            CSV file and options.

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        Response[BrdfFit | ErrorBody]
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
    body: BrdfFitRequest,

) -> BrdfFit | ErrorBody | None:
    """ Fit a material model to measured BRDF samples.

     What `glint fit-brdf` does with a CSV file: bounded, robust (Huber by default)
    Levenberg–Marquardt from several starts; the parameters come back under the names a
    request's material takes, with 1σ uncertainties from the Jacobian at the optimum.

    Args:
        body (BrdfFitRequest): The body of `POST /v1/fits/brdf`: what `glint fit-brdf` takes as a
            CSV file and options.

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        BrdfFit | ErrorBody
     """


    return sync_detailed(
        client=client,
body=body,

    ).parsed

async def asyncio_detailed(
    *,
    client: AuthenticatedClient | Client,
    body: BrdfFitRequest,

) -> Response[BrdfFit | ErrorBody]:
    """ Fit a material model to measured BRDF samples.

     What `glint fit-brdf` does with a CSV file: bounded, robust (Huber by default)
    Levenberg–Marquardt from several starts; the parameters come back under the names a
    request's material takes, with 1σ uncertainties from the Jacobian at the optimum.

    Args:
        body (BrdfFitRequest): The body of `POST /v1/fits/brdf`: what `glint fit-brdf` takes as a
            CSV file and options.

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        Response[BrdfFit | ErrorBody]
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
    body: BrdfFitRequest,

) -> BrdfFit | ErrorBody | None:
    """ Fit a material model to measured BRDF samples.

     What `glint fit-brdf` does with a CSV file: bounded, robust (Huber by default)
    Levenberg–Marquardt from several starts; the parameters come back under the names a
    request's material takes, with 1σ uncertainties from the Jacobian at the optimum.

    Args:
        body (BrdfFitRequest): The body of `POST /v1/fits/brdf`: what `glint fit-brdf` takes as a
            CSV file and options.

    Raises:
        errors.UnexpectedStatus: If the server returns an undocumented status code and Client.raise_on_unexpected_status is True.
        httpx.TimeoutException: If the request takes longer than Client.timeout.

    Returns:
        BrdfFit | ErrorBody
     """


    return (await asyncio_detailed(
        client=client,
body=body,

    )).parsed
