-- wrk script: POST the request file named by GLINT_LOADTEST_BODY as JSON.
wrk.method = "POST"
wrk.headers["Content-Type"] = "application/json"
local f = assert(io.open(os.getenv("GLINT_LOADTEST_BODY"), "rb"))
wrk.body = f:read("*a")
f:close()
