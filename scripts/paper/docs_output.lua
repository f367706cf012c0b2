-- SPDX-License-Identifier: GPL-3.0-or-later
-- SPDX-FileCopyrightText: 2026 The dda maintainers
-- docs_output.lua: how the report scripts (validation_report.lua,
-- blast_summary.lua) write into docs/, shared so that both follow the same
-- rules:
--   * only when asked (--set write_docs=true); otherwise into the --out folder;
--   * never deleting what they did not compute: CSV rows are merged by key
--     (figure, quantity), marked blocks of a Markdown file are replaced;
--   * whole files or nothing: each file is written beside itself and renamed
--     over the old one, every write checked.

local M = {}

-- Writes text to path (through path.part); raises naming the file on failure.
function M.write(path, text)
  local part = path .. ".part"
  local f, err = io.open(part, "wb")
  if not f then error("cannot write " .. path .. ": " .. tostring(err), 0) end
  local ok, werr = f:write(text)
  local closed, cerr = f:close()
  if not ok or not closed then
    os.remove(part)
    error("cannot write " .. path .. ": " .. tostring(werr or cerr), 0)
  end
  local renamed, rerr = os.rename(part, path)
  if not renamed then
    os.remove(part)
    error("cannot write " .. path .. ": " .. tostring(rerr), 0)
  end
end

-- Closes a file written with io.open and f:write, raising naming the file if
-- any of its writes failed (a full disk shows at the latest when the buffer
-- is flushed on close).
function M.close(f, path)
  local ok, err = f:close()
  if not ok then error("cannot write " .. path .. ": " .. tostring(err), 2) end
end

function M.read(path)
  local f = io.open(path, "rb")
  if not f then return nil end
  local text = f:read("a")
  f:close()
  return text
end

local function csv_key(line)
  local figure, quantity = line:match("^([^,]*),([^,]*)")
  return figure and (figure .. "," .. quantity) or line
end

-- Merges `lines` (CSV rows "figure,quantity,...") into the CSV file at path:
-- a row whose (figure, quantity) is among them is replaced in place, the new
-- ones are appended, every other row is kept. Returns the counts replaced,
-- added and kept.
function M.merge_csv(path, header, lines)
  local new, order = {}, {}
  for _, l in ipairs(lines) do
    local k = csv_key(l)
    if not new[k] then order[#order + 1] = k end
    new[k] = l
  end
  local out, seen, replaced, kept = { header }, {}, 0, 0
  for l in ((M.read(path) or "") .. "\n"):gmatch("([^\n]*)\n") do
    if l ~= "" and l ~= header then
      local k = csv_key(l)
      if new[k] then
        if not seen[k] then out[#out + 1] = new[k]; replaced = replaced + 1 end
        seen[k] = true
      else
        out[#out + 1] = l
        kept = kept + 1
      end
    end
  end
  local added = 0
  for _, k in ipairs(order) do
    if not seen[k] then out[#out + 1] = new[k]; added = added + 1 end
  end
  M.write(path, table.concat(out, "\n") .. "\n")
  return replaced, added, kept
end

-- The text between the begin and end marker lines (both included) of a
-- file's text, and where it starts and ends; nil when absent.
function M.find_block(text, begin_marker, end_marker)
  local b = text:find(begin_marker, 1, true)
  if not b then return nil end
  local _, e = text:find(end_marker, b, true)
  if not e then error("the marker '" .. begin_marker .. "' has no end marker after it; fix the file by hand", 0) end
  return text:sub(b, e), b, e
end

-- Replaces the marked block of the Markdown file at path with `block`
-- (appended at the end when the file has none); the rest stays as it is.
function M.replace_block(path, begin_marker, end_marker, block)
  local old = M.read(path) or ""
  local _, b, e = M.find_block(old, begin_marker, end_marker)
  local new
  if b then
    new = old:sub(1, b - 1) .. block .. old:sub(e + 1)
  else
    new = old:gsub("%s+$", "") .. (old ~= "" and "\n\n" or "") .. block .. "\n"
  end
  M.write(path, new)
end

return M
