-- wrk script: POST the request file named by GLINT_LOADTEST_BODY as JSON, and count the
-- answers by status across all threads (printed as `status CODE COUNT` lines at the end).
wrk.method = "POST"
wrk.headers["Content-Type"] = "application/json"
local f = assert(io.open(os.getenv("GLINT_LOADTEST_BODY"), "rb"))
wrk.body = f:read("*a")
f:close()

local threads = {}

function setup(thread)
   table.insert(threads, thread)
end

function init(args)
   counts = {}
end

function response(status, headers, body)
   counts[status] = (counts[status] or 0) + 1
end

function done(summary, latency, requests)
   local total = {}
   for _, t in ipairs(threads) do
      for status, n in pairs(t:get("counts")) do
         total[status] = (total[status] or 0) + n
      end
   end
   for status, n in pairs(total) do
      io.write(string.format("status %d %d\n", status, n))
   end
end
