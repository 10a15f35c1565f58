# glint HTTP service.
#
#   docker build -t glint .
#   docker run -p 8080:8080 -e GLINT_API_TOKEN=change-me -v glint-data:/data glint
#
# Inside the container the service listens on 0.0.0.0:8080 (GLINT_ADDR), so it refuses to
# start without GLINT_API_TOKEN; set GLINT_ALLOW_UNAUTHENTICATED=true instead only behind
# something that authenticates for it. /healthz and /readyz never need the token, so the
# HEALTHCHECK works either way.

# ---- build: the Rust toolchain image, the same command as on a workstation ----
FROM rust:1.95-slim-bookworm AS build
WORKDIR /src
COPY . .
# Cache mounts keep the registry and target/ between builds (BuildKit).
RUN --mount=type=cache,target=/usr/local/cargo/registry \
    --mount=type=cache,target=/src/target \
    cargo build --release --locked --bin glint \
 && install -m 0755 target/release/glint /usr/local/bin/glint

# ---- run: slim Debian (same glibc as the build image), non-root ----
FROM debian:bookworm-slim
RUN useradd --system --uid 10001 --user-group --home-dir /data --shell /usr/sbin/nologin glint \
 && mkdir -p /data && chown glint:glint /data
COPY --from=build /usr/local/bin/glint /usr/local/bin/glint
USER glint
ENV GLINT_ADDR=0.0.0.0:8080 \
    GLINT_DATA_DIR=/data
VOLUME ["/data"]
EXPOSE 8080
# `glint healthcheck` GETs /healthz over loopback: no curl in the image.
HEALTHCHECK --interval=15s --timeout=5s --start-period=10s --retries=3 \
    CMD ["glint", "healthcheck"]
STOPSIGNAL SIGTERM
ENTRYPOINT ["glint"]
CMD ["serve"]
