-- urdf-lint language server for Neovim (0.7+): diagnostics, fixes, navigation, hover,
-- completion, rename and formatting on xacro, URDF, SRDF, the YAML files they load and the
-- config (pyproject.toml, urdf-lint.toml). Put in your init.lua:
--   dofile("/path/to/urdf-lint/editors/neovim/urdf_lint.lua")
-- `urdf-lint` must be on PATH (or set vim.g.urdf_lint_cmd = {"/path/.venv/bin/urdf-lint", "server"}).
--
-- One server per workspace root, shared by every file below it: the git repository holding
-- the file, else the nearest folder with a package.xml or pyproject.toml, else the working
-- directory. A xacro, URDF or SRDF file starts the server of its root; a YAML or config file
-- joins the server of its root once one runs (a YAML file alone starts nothing).
local M = {}
local clients = {} -- root -> client id

local ROBOT = { xacro = true, urdf = true, srdf = true }
local JOINS = { yaml = true, yml = true }
local CONFIG = { ["pyproject.toml"] = true, ["urdf-lint.toml"] = true, [".urdf-lint.toml"] = true }

-- what a file is to urdf-lint: "robot" (starts the server), "joins" (attaches to a running
-- one) or nil
local function kind(fname)
  local ext = fname:match("%.([%w]+)$")
  if ext and ROBOT[ext] then
    return "robot"
  end
  if (ext and JOINS[ext]) or CONFIG[vim.fn.fnamemodify(fname, ":t")] then
    return "joins"
  end
  return nil
end

local function upward(name, dir, is_dir)
  local found = is_dir and vim.fn.finddir(name, dir .. ";") or vim.fn.findfile(name, dir .. ";")
  if found == "" then
    return nil
  end
  return vim.fn.fnamemodify(found, ":p"):gsub("/$", ""):match("^(.*)/[^/]*$")
end

function M.root(fname)
  local dir = vim.fn.fnamemodify(fname, ":p:h")
  local git = upward(".git", dir, true) or upward(".git", dir, false) -- (a worktree: a file)
  if git then
    return git
  end
  local best
  for _, marker in ipairs({ "package.xml", "pyproject.toml" }) do
    local r = upward(marker, dir, false)
    if r and (not best or #r > #best) then
      best = r -- the nearest
    end
  end
  return best or vim.fn.getcwd()
end

local function running(root)
  local id = clients[root]
  local client = id and vim.lsp.get_client_by_id(id)
  if client and not client.is_stopped() then
    return id
  end
  clients[root] = nil
  return nil
end

local function below(fname, root)
  local p = vim.fn.fnamemodify(fname, ":p")
  return p:sub(1, #root + 1) == root .. "/"
end

-- attach the buffer to the server of its root, starting it when the buffer is a robot file
function M.start(bufnr)
  local fname = vim.api.nvim_buf_get_name(bufnr)
  local what = kind(fname)
  if fname == "" or not what then
    return
  end
  local root = M.root(fname)
  local id = running(root)
  if not id then
    if what ~= "robot" then
      return
    end
    id = vim.lsp.start_client({
      name = "urdf-lint",
      cmd = vim.g.urdf_lint_cmd or { "urdf-lint", "server" },
      root_dir = root,
      workspace_folders = { { uri = vim.uri_from_fname(root), name = root } },
      handlers = vim.g.urdf_lint_handlers,
      on_exit = function()
        clients[root] = nil
      end,
    })
    if not id then
      return
    end
    clients[root] = id
    -- the YAML and config files already open below the root join it
    for _, b in ipairs(vim.api.nvim_list_bufs()) do
      local name = vim.api.nvim_buf_get_name(b)
      if b ~= bufnr and vim.api.nvim_buf_is_loaded(b) and kind(name) and below(name, root) then
        vim.lsp.buf_attach_client(b, id)
      end
    end
  end
  vim.lsp.buf_attach_client(bufnr, id) -- (once per buffer and client: Neovim ignores a repeat)
end

-- one autocmd, its patterns together: a file matching two (`*.urdf.xacro`) fires it once
vim.api.nvim_create_augroup("urdf_lint", { clear = true })
vim.api.nvim_create_autocmd({ "BufReadPost", "BufNewFile" }, {
  group = "urdf_lint",
  pattern = { "*.xacro", "*.urdf", "*.srdf", "*.yaml", "*.yml", "pyproject.toml",
    "urdf-lint.toml", ".urdf-lint.toml" },
  callback = function(args)
    M.start(args.buf)
  end,
})
return M
