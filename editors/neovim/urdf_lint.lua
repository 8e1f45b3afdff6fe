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
--
-- :UrdfLintPreview opens the 3D preview of the current file (docs/preview.md): it follows the
-- unsaved buffer, its highlight follows the cursor (CursorHold), and a click in the page moves
-- the cursor here (window/showDocument, answered below where Neovim has no handler of its own).
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
    local capabilities = vim.lsp.protocol.make_client_capabilities()
    capabilities.window = capabilities.window or {}
    capabilities.window.showDocument = { support = true }
    id = vim.lsp.start_client({
      name = "urdf-lint",
      cmd = vim.g.urdf_lint_cmd or { "urdf-lint", "server" },
      root_dir = root,
      workspace_folders = { { uri = vim.uri_from_fname(root), name = root } },
      capabilities = capabilities,
      handlers = vim.tbl_extend("keep", vim.g.urdf_lint_handlers or {}, {
        ["window/showDocument"] = vim.lsp.handlers["window/showDocument"] or M.show_document,
      }),
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

-- window/showDocument (Neovim before 0.8 has no handler): a file of the workspace at the
-- selection's start; never an external program
function M.show_document(_, result)
  if not result or result.external or not result.uri:match("^file://") then
    return { success = false }
  end
  local fname = vim.uri_to_fname(result.uri)
  local bufnr = vim.fn.bufadd(fname)
  vim.fn.bufload(bufnr)
  vim.api.nvim_win_set_buf(0, bufnr)
  if result.selection then
    local pos = result.selection.start
    pcall(vim.api.nvim_win_set_cursor, 0, { pos.line + 1, pos.character })
  end
  return { success = true }
end

local previewed = {} -- bufnr -> true once its preview is open: CursorHold moves the highlight

local function at_cursor(bufnr)
  local p = vim.api.nvim_win_get_cursor(0)
  return { vim.uri_from_bufnr(bufnr), p[1] - 1, p[2] }
end

function M.preview(bufnr, done)
  bufnr = bufnr or vim.api.nvim_get_current_buf()
  local args = at_cursor(bufnr)
  vim.lsp.buf_request(bufnr, "workspace/executeCommand",
    { command = "urdf-lint.preview", arguments = args }, function(err, result)
      if err or not result then
        vim.notify("urdf-lint preview: " .. (err and err.message or "no answer"), vim.log.levels.ERROR)
        return
      end
      previewed[bufnr] = true
      vim.notify("urdf-lint preview: " .. result.url)
      if vim.g.urdf_lint_open_preview ~= false and vim.ui and vim.ui.open then
        vim.ui.open(result.url) -- (Neovim 0.10+; before it, open the printed URL)
      end
      if done then
        done(result)
      end
    end)
end

vim.api.nvim_create_user_command("UrdfLintPreview", function()
  M.preview()
end, {})

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
vim.api.nvim_create_autocmd("CursorHold", {
  group = "urdf_lint",
  callback = function(args)
    if previewed[args.buf] then
      vim.lsp.buf_request(args.buf, "workspace/executeCommand",
        { command = "urdf-lint.previewHighlight", arguments = at_cursor(args.buf) },
        function() end)
    end
  end,
})
return M
