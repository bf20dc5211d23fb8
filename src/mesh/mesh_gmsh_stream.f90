!> A Gmsh ASCII mesh (2.2 or 4.1) read in chunks, for runs on any number of
!> ranks: rank 0 streams the file through the parser (mesh_gmsh_parse) and
!> sends what it reads on in chunks of at most 1 MB; every rank keeps the
!> nodes whose tags fall in its block of the tag range, the hexahedra of its
!> zone range and its block of the quadrilaterals. The checks of the
!> whole-file reader (mesh_gmsh) are made on the distributed data, with the
!> same messages. Two passes over the file: gmsh_scan (nodes, groups, the
!> used nodes' ids), then range_add_gmsh (zones and face sets).
module mesh_gmsh_stream
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use core_kinds, only: rk, ik, i8
  use core_status, only: status_t
  use core_sort, only: sort_order
  use core_text, only: i8toa => to_text
  use core_sort, only: sort_unique, sorted_find
  use mesh_geometry, only: hex_volume, HEX_FACE_NODES, quad_vector_area
  use mesh_global, only: NAME_LEN
  use mesh_range, only: mesh_range_t, range_grow_faces
  use mesh_report, only: merge_capped, keyed_report_t, LINE_LEN
  use mesh_gmsh_parse, only: gmsh_header_t, gmsh_sink_t, gmsh_parse, gmsh_groups, &
      sorted_key, same_cycle, find_sorted, MAX_REPORT, SHIFT
  use parallel_env, only: par_rank, par_size, par_sum, par_max, par_bcast
  use parallel_route, only: par_block_owner, par_route_free, par_exscan_i8, &
      par_ordered_sum, par_allgather_text
  implicit none
  private
  public :: gmsh_scan, range_add_gmsh

  !> Words (64-bit) of a chunk rank 0 sends while it streams a file (1 MB:
  !> rank 0's buffers for a chunk, packed and received, stay near 3 MB).
  integer, parameter :: CHUNK_WORDS = 131072
  !> What rank 0 is doing with the file: streaming its nodes and the
  !> hexahedra's node tags (gmsh_scan), or its hexahedra and quadrilaterals
  !> (range_add_gmsh).
  integer, parameter :: MODE_SCAN = 1, MODE_ZONES = 2
  !> Chunks rank 0 sends while it streams (the other ranks serve them).
  integer, parameter :: CMD_END = 0, CMD_LAYOUT = 1, CMD_NODES = 2, CMD_NODES_DONE = 3, &
      CMD_USED = 4, CMD_HEX = 5, CMD_QUAD = 6
  !> Words of a record of each chunk kind.
  integer, parameter :: WIDTH(CMD_NODES:CMD_QUAD) = [5, 0, 1, 11, 7]

  !> A Gmsh file read in chunks (gmsh_scan, then range_add_gmsh): rank 0
  !> streams it; every rank holds the nodes whose tags fall in its block of
  !> the tag range, and later the hexahedra of its zone range and its block
  !> of the quadrilaterals. Sizes and names are the same on every rank.
  type, public :: gmsh_part_t
    character(len=:), allocatable :: path
    integer(i8) :: nhex = 0 !< hexahedra (= zones)
    integer(i8) :: nquad = 0 !< quadrilaterals in 2D groups (one per group)
    integer(i8) :: nnode = 0 !< nodes used by the hexahedra
    integer, allocatable :: block_tags(:), set_tags(:) !< sorted 3D and 2D physical tags
    character(len=NAME_LEN), allocatable :: block_names(:), set_names(:)
    logical, allocatable :: block_used(:) !< the 3D group holds hexahedra
    integer(i8), allocatable :: set_count(:) !< faces of each set (range_add_gmsh)
    !> Node tags tag_lo .. tag_lo + ntag - 1 are spread over the ranks in
    !> blocks (smaller tags go to rank 0, larger to the last rank).
    integer(i8) :: tag_lo = 1, ntag = 1
    integer :: nstore = 0
    !> (6, nstore) this rank's nodes sorted by tag: tag, index in $Nodes,
    !> x, y, z (bits), id (1.. in tag order over the used nodes, 0 unused)
    integer(i8), allocatable :: store(:, :)
    integer(i8), allocatable :: hex_tag(:) !< (range%nzone) Gmsh tags of the range's hexahedra
    integer :: nq = 0
    integer(i8), allocatable :: quads(:, :) !< (7, nq) [index, tag, group, 4 node tags]
  end type gmsh_part_t

  !> Rank 0's sink while it streams the file: what it reads goes on to the
  !> ranks in chunks; kept are the groups seen and counts.
  type, extends(gmsh_sink_t) :: stream_sink_t
    integer :: mode = MODE_SCAN
    type(gmsh_part_t), pointer :: part => null()
    type(mesh_range_t), pointer :: range => null()
    integer(i8) :: zone0 = 0 !< zones of the parts before this one
    character(len=:), allocatable :: prefix
    integer :: buf_cmd = -1, nbuf = 0
    integer(i8), allocatable :: buf(:, :)
    integer, allocatable :: buf_dest(:)
    integer(i8) :: nstream_node = 0, nstream_hex = 0, nstream_quad = 0
    integer, allocatable :: hex_groups(:), quad_groups(:) !< distinct physical tags seen
    integer :: nnogroup = 0 !< hexahedra in no 3D group
    character(len=LINE_LEN) :: nogroup(10) = ''
  contains
    procedure :: nodes_begin => stream_layout
    procedure :: node => stream_node
    procedure :: nodes_done => stream_nodes_done
    procedure :: hex => stream_hex
    procedure :: quad => stream_quad
  end type stream_sink_t

contains

  ! ---------------------------------------------------------------------------
  ! Read in chunks: rank 0 streams the file, every rank keeps its share
  ! ---------------------------------------------------------------------------

  !> The rank that keeps node tag (its block of the part's tag range; tags
  !> outside the range go to the first or last rank).
  integer function tag_owner(part, tag) result(r)
    type(gmsh_part_t), intent(in) :: part
    integer(i8), intent(in) :: tag
    r = par_block_owner(part%ntag, par_size(), min(max(tag - part%tag_lo + 1, 1_i8), &
        part%ntag))
  end function tag_owner

  !> Rank 0 tells the others what comes next (cmd and two numbers).
  subroutine send_command(cmd, a, b)
    integer, intent(in) :: cmd
    integer(i8), intent(in) :: a, b
    integer(i8) :: c(3)
    c = [int(cmd, i8), a, b]
    call par_bcast(c)
  end subroutine send_command

  !> The node tags' layout: tags lo .. lo + n - 1 in blocks over the ranks.
  subroutine stream_layout(data, lo, n, ok)
    class(stream_sink_t), intent(inout) :: data
    integer(i8), intent(in) :: lo
    integer, intent(in) :: n
    logical, intent(out) :: ok
    ok = .true.
    data%part%tag_lo = lo
    data%part%ntag = max(int(n, i8), 1_i8)
    call send_command(CMD_LAYOUT, data%part%tag_lo, data%part%ntag)
  end subroutine stream_layout

  !> One record of kind cmd for rank dest into rank 0's chunk (sent when full).
  subroutine emit(data, cmd, rec, dest)
    class(stream_sink_t), intent(inout) :: data
    integer, intent(in) :: cmd
    integer(i8), intent(in) :: rec(:)
    integer, intent(in) :: dest
    if (data%buf_cmd /= cmd .and. data%nbuf > 0) call flush(data)
    if (data%nbuf == 0) then
      data%buf_cmd = cmd
      if (allocated(data%buf)) then
        if (size(data%buf, 1) /= WIDTH(cmd)) deallocate(data%buf)
      end if
      if (.not. allocated(data%buf)) allocate(data%buf(WIDTH(cmd), CHUNK_WORDS / WIDTH(cmd)))
      if (.not. allocated(data%buf_dest)) allocate(data%buf_dest(CHUNK_WORDS))
    end if
    data%nbuf = data%nbuf + 1
    data%buf(:, data%nbuf) = rec
    data%buf_dest(data%nbuf) = dest
    if (data%nbuf == size(data%buf, 2)) call flush(data)
  end subroutine emit

  !> Send rank 0's chunk (every rank takes part in deliver).
  subroutine flush(data)
    class(stream_sink_t), intent(inout) :: data
    if (data%nbuf == 0) return
    call send_command(data%buf_cmd, int(data%nbuf, i8), 0_i8)
    call deliver(data%buf_cmd, data%part, data%range, data%buf, data%buf_dest(:data%nbuf))
    data%nbuf = 0
  end subroutine flush

  !> A chunk's records to their ranks, kept there (collective).
  subroutine deliver(cmd, part, range, send, dest)
    integer, intent(in) :: cmd
    type(gmsh_part_t), intent(inout) :: part
    type(mesh_range_t), intent(inout) :: range
    !> (width, >= size(dest)) the chunk (its first size(dest) records); freed
    integer(i8), allocatable, intent(inout) :: send(:, :)
    integer, intent(in) :: dest(:)
    integer(i8), allocatable :: recv(:, :), grown(:, :)
    integer :: i, m, p, local
    call par_route_free(send, dest, recv)
    m = size(recv, 2)
    select case (cmd)
    case (CMD_NODES)
      if (part%nstore + m > size(part%store, 2)) then
        allocate(grown(6, max(part%nstore + m, 2 * size(part%store, 2))))
        grown(:, :part%nstore) = part%store(:, :part%nstore)
        call move_alloc(grown, part%store)
      end if
      part%store(1:5, part%nstore + 1:part%nstore + m) = recv
      part%store(6, part%nstore + 1:part%nstore + m) = 0
      part%nstore = part%nstore + m
    case (CMD_USED)
      do i = 1, m
        p = find_store(part, recv(1, i))
        if (p > 0) part%store(6, p) = 1
      end do
    case (CMD_HEX)
      do i = 1, m
        local = int(recv(1, i) - range%first) + 1
        range%conn(:, local) = recv(4:11, i)
        range%zone_block(local) = int(recv(3, i), ik)
        part%hex_tag(local) = recv(2, i)
      end do
    case (CMD_QUAD)
      if (part%nq + m > size(part%quads, 2)) then
        allocate(grown(7, max(part%nq + m, 2 * size(part%quads, 2))))
        grown(:, :part%nq) = part%quads(:, :part%nq)
        call move_alloc(grown, part%quads)
      end if
      part%quads(:, part%nq + 1:part%nq + m) = recv
      part%nq = part%nq + m
    end select
  end subroutine deliver

  !> Column of the first stored node with tag (the store sorted), 0 if none.
  integer function find_store(part, tag) result(p)
    type(gmsh_part_t), intent(in) :: part
    integer(i8), intent(in) :: tag
    integer :: lo, hi, mid
    lo = 1
    hi = part%nstore + 1
    do while (lo < hi)
      mid = (lo + hi) / 2
      if (part%store(1, mid) < tag) then
        lo = mid + 1
      else
        hi = mid
      end if
    end do
    p = 0
    if (lo <= part%nstore) then
      if (part%store(1, lo) == tag) p = lo
    end if
  end function find_store

  !> This rank's nodes sorted by tag, then by place in $Nodes.
  subroutine sort_store(part)
    type(gmsh_part_t), intent(inout) :: part
    integer, allocatable :: order(:)
    call sort_order(part%store(1:2, :part%nstore), order)
    part%store = part%store(:, order)
    part%nstore = size(order)
  end subroutine sort_store

  !> The ranks other than 0 while rank 0 streams: take part in its chunks.
  subroutine stream_serve(part, range)
    type(gmsh_part_t), intent(inout) :: part
    type(mesh_range_t), intent(inout) :: range
    integer(i8) :: c(3)
    integer(i8), allocatable :: empty(:, :)
    integer :: none(0)
    do
      c = 0
      call par_bcast(c)
      select case (int(c(1)))
      case (CMD_END)
        exit
      case (CMD_LAYOUT)
        part%tag_lo = c(2)
        part%ntag = c(3)
      case (CMD_NODES_DONE)
        call sort_store(part)
      case default
        allocate(empty(WIDTH(int(c(1))), 0))
        call deliver(int(c(1)), part, range, empty, none)
      end select
    end do
  end subroutine stream_serve

  !> Rank 0: a node of $Nodes to the owner of its tag.
  subroutine stream_node(data, tag, xyz)
    class(stream_sink_t), intent(inout) :: data
    integer(i8), intent(in) :: tag
    real(rk), intent(in) :: xyz(3)
    data%nstream_node = data%nstream_node + 1
    call emit(data, CMD_NODES, [tag, data%nstream_node, transfer(xyz(1), 1_i8), &
        transfer(xyz(2), 1_i8), transfer(xyz(3), 1_i8)], tag_owner(data%part, tag))
  end subroutine stream_node

  !> Rank 0: the end of $Nodes (every rank sorts its nodes).
  subroutine stream_nodes_done(data)
    class(stream_sink_t), intent(inout) :: data
    call flush(data)
    call send_command(CMD_NODES_DONE, 0_i8, 0_i8)
    call sort_store(data%part)
  end subroutine stream_nodes_done

  !> Rank 0: a hexahedron. Scan: its group noted, its node tags marked used
  !> by their owners; zones: the whole record to the rank of its zone.
  subroutine stream_hex(data, tag, nodes, phys)
    class(stream_sink_t), intent(inout) :: data
    integer(i8), intent(in) :: tag, nodes(8)
    integer, intent(in) :: phys
    integer(i8) :: g
    integer :: k
    data%nstream_hex = data%nstream_hex + 1
    if (data%mode == MODE_SCAN) then
      if (phys /= 0) then
        call add_distinct(data%hex_groups, phys)
      else
        data%nnogroup = data%nnogroup + 1
        if (data%nnogroup <= size(data%nogroup)) data%nogroup(data%nnogroup) = &
            data%prefix//'hexahedron '//i8toa(tag)//' is in no 3D physical group (every '// &
            'zone needs a block: define Physical Volumes)'
      end if
      do k = 1, 8
        call emit(data, CMD_USED, [nodes(k)], tag_owner(data%part, nodes(k)))
      end do
    else
      g = data%zone0 + data%nstream_hex
      call emit(data, CMD_HEX, [g, tag, int(phys, i8), nodes], &
          par_block_owner(data%range%nzone_global, par_size(), g))
    end if
  end subroutine stream_hex

  !> Rank 0: a quadrilateral of a 2D group (scan: its group noted; zones: to
  !> the rank of its block of the quadrilaterals).
  subroutine stream_quad(data, tag, nodes, phys)
    class(stream_sink_t), intent(inout) :: data
    integer(i8), intent(in) :: tag, nodes(4)
    integer, intent(in) :: phys
    data%nstream_quad = data%nstream_quad + 1
    if (data%mode == MODE_SCAN) then
      call add_distinct(data%quad_groups, phys)
    else
      call emit(data, CMD_QUAD, [data%nstream_quad, tag, int(phys, i8), nodes], &
          par_block_owner(data%part%nquad, par_size(), data%nstream_quad))
    end if
  end subroutine stream_quad

  !> value into the list if not there yet.
  subroutine add_distinct(list, value)
    integer, allocatable, intent(inout) :: list(:)
    integer, intent(in) :: value
    if (.not. allocated(list)) allocate(list(0))
    if (any(list == value)) return
    list = [list, value]
  end subroutine add_distinct

  !> Rank 0 streams the file with data%mode set; the other ranks serve.
  !> Problems of the parse are added to status on rank 0 only.
  subroutine stream_file(path, prefix, head, data, part, range, status)
    character(len=*), intent(in) :: path, prefix
    type(gmsh_header_t), intent(inout) :: head
    type(stream_sink_t), intent(inout) :: data
    type(gmsh_part_t), intent(inout), target :: part
    type(mesh_range_t), intent(inout), target :: range
    type(status_t), intent(inout) :: status
    logical :: parsed
    if (par_rank() /= 0) then
      call stream_serve(part, range)
      return
    end if
    data%part => part
    data%range => range
    data%prefix = prefix
    data%skip_nodes = data%mode == MODE_ZONES
    data%nodes_first = data%mode == MODE_SCAN
    call gmsh_parse(path, prefix, head, data, status, parsed)
    if (parsed) call flush(data)
    data%nbuf = 0
    call send_command(CMD_END, 0_i8, 0_i8)
  end subroutine stream_file

  !> First pass of a read in chunks (collective): rank 0 streams the file,
  !> sending the nodes to the owners of their tags and the hexahedra's node
  !> tags to the same owners (which mark them used), and keeps only the
  !> groups seen and counts; then the blocks and sets are named, repeated
  !> node tags found and the used nodes numbered in tag order. Every rank
  !> ends with the same problems in status.
  subroutine gmsh_scan(path, part, status)
    character(len=*), intent(in) :: path
    type(gmsh_part_t), intent(inout), target :: part
    type(status_t), intent(inout) :: status
    type(gmsh_header_t) :: head
    type(stream_sink_t) :: data
    type(mesh_range_t), target :: none
    character(len=:), allocatable :: prefix
    character(len=LINE_LEN), allocatable :: lines(:), all(:)
    integer(i8) :: sizes(4), nused, before
    integer :: count0, i, nbad

    prefix = "mesh file '"//trim(path)//"': "
    part%path = path
    count0 = status%count
    allocate(part%store(6, 1024), part%quads(7, 0), part%hex_tag(0))
    allocate(part%block_tags(0), part%set_tags(0), part%block_names(0), part%set_names(0))
    data%mode = MODE_SCAN
    call stream_file(path, prefix, head, data, part, none, status)
    if (par_rank() == 0 .and. status%count == count0) call scan_groups(head, data, prefix, part, &
        status)
    ! Rank 0's problems to every rank.
    allocate(lines(0))
    if (par_rank() == 0 .and. status%count > count0) then
      deallocate(lines)
      allocate(lines(max(0, min(status%count, size(status%messages)) - count0)))
      do i = 1, size(lines)
        lines(i) = status%messages(count0 + i)
      end do
    end if
    call par_allgather_text(lines, all)
    if (par_rank() /= 0) then
      do i = 1, size(all)
        call status%add(trim(all(i)))
      end do
    end if
    if (size(all) > 0) return
    ! Sizes and names to every rank.
    sizes = [data%nstream_hex, data%nstream_quad, int(size(part%block_tags), i8), &
        int(size(part%set_tags), i8)]
    call par_bcast(sizes)
    part%nhex = sizes(1)
    part%nquad = sizes(2)
    if (par_rank() /= 0) then
      deallocate(part%block_tags, part%set_tags, part%block_names, part%set_names)
      allocate(part%block_tags(sizes(3)), part%set_tags(sizes(4)), &
          part%block_names(sizes(3)), part%set_names(sizes(4)), part%block_used(sizes(3)))
    end if
    call par_bcast(part%block_used)
    call par_bcast(part%block_tags)
    call par_bcast(part%set_tags)
    call par_bcast(part%block_names)
    call par_bcast(part%set_names)
    ! Repeated tags (tag order is rank order), then the used nodes' ids.
    deallocate(lines)
    allocate(lines(10))
    nbad = 0
    do i = 2, part%nstore
      if (part%store(1, i) /= part%store(1, i - 1)) cycle
      nbad = nbad + 1
      if (nbad <= size(lines)) lines(nbad) = prefix//'node tag '//i8toa(part%store(1, i))// &
          ' appears more than once in $Nodes'
    end do
    call merge_capped(status, prefix, lines, nbad, 'repeated node tags')
    nused = count(part%store(6, :part%nstore) > 0)
    before = par_exscan_i8(nused)
    part%nnode = par_sum(nused)
    nused = 0
    do i = 1, part%nstore
      if (part%store(6, i) == 0) cycle
      nused = nused + 1
      part%store(6, i) = before + nused
    end do
  end subroutine gmsh_scan

  !> Rank 0 after the scan: the checks of the whole-file reader that need
  !> only the groups seen (no hexahedra; names of the groups; hexahedra in
  !> no group).
  subroutine scan_groups(head, data, prefix, part, status)
    type(gmsh_header_t), intent(in) :: head
    type(stream_sink_t), intent(inout) :: data
    character(len=*), intent(in) :: prefix
    type(gmsh_part_t), intent(inout) :: part
    type(status_t), intent(inout) :: status
    integer :: i
    if (.not. allocated(data%hex_groups)) allocate(data%hex_groups(0))
    if (.not. allocated(data%quad_groups)) allocate(data%quad_groups(0))
    call gmsh_groups(head, prefix, data%nstream_hex, data%hex_groups, data%quad_groups, &
        part%block_tags, part%set_tags, part%block_names, part%set_names, status)
    if (data%nstream_hex == 0) return
    part%block_used = [(any(data%hex_groups == part%block_tags(i)), i = 1, size(part%block_tags))]
    do i = 1, min(data%nnogroup, size(data%nogroup))
      call status%add(trim(data%nogroup(i)))
    end do
    call status%add_more(prefix, data%nnogroup, MAX_REPORT, 'hexahedra in no 3D physical group')
  end subroutine scan_groups

  !> Second pass (collective): rank 0 streams the file again, sending each
  !> hexahedron to the rank of its zone (global id zone0 + its place) and the
  !> quadrilaterals in blocks; the nodes' owners answer the ids and positions
  !> of the tags each rank's zones and quadrilaterals use; then the checks of
  !> build_mesh, the matching of quadrilaterals to hexahedron faces (by the
  !> owners of the faces' smallest node) and the face sets (sorted by zone
  !> and face, repeats dropped, as build_sets makes them), all distributed.
  !> part%set_count: the faces of each set (the range's set counts are the
  !> caller's). summary: mesh_import_summary's lines, bitwise on any rank
  !> count. lo..hi: the range positions filled.
  subroutine range_add_gmsh(range, part, zone0, node0, sets, ord0, lo, hi, title, summary, &
      status)
    type(mesh_range_t), intent(inout), target :: range
    type(gmsh_part_t), intent(inout), target :: part
    integer(i8), intent(in) :: zone0, node0
    integer, intent(in) :: sets(:, :) !< (2, nset of the part)
    integer(i8), intent(in) :: ord0(:, :) !< (2, nset of the part)
    integer, intent(out) :: lo, hi
    character(len=*), intent(in) :: title
    character(len=200), allocatable, intent(out) :: summary(:)
    type(status_t), intent(inout) :: status
    type(gmsh_header_t) :: head
    type(stream_sink_t) :: data
    type(status_t) :: again
    type(keyed_report_t) :: keyed
    character(len=:), allocatable :: prefix
    character(len=LINE_LEN) :: lines(MAX_REPORT)
    character(len=24) :: text
    integer(i8), allocatable :: ids(:), send(:, :), recv(:, :), answer(:, :), key(:), ans(:, :)
    integer(i8), allocatable :: faces(:, :), entries(:, :), cnt(:), off(:), quads(:, :), &
        best2(:, :)
    integer, allocatable :: dest(:), source(:), order(:)
    real(rk), allocatable :: value(:, :), vol(:), volume(:)
    real(rk) :: total(4), p(3, 4), a
    integer(i8) :: zfirst, zlast, g, fk(2), kk(4)
    integer :: nz, i, j, k, c, f, n, nbad, s, m, pos, nset, cand, nid(4)
    logical :: unknown

    prefix = "mesh file '"//trim(part%path)//"': "
    nset = size(part%set_tags)
    zfirst = max(zone0 + 1, range%first)
    zlast = min(zone0 + part%nhex, range%first + range%nzone - 1)
    lo = int(zfirst - range%first) + 1
    hi = int(zlast - range%first) + 1
    nz = max(0, hi - lo + 1)
    allocate(summary(0), part%set_count(nset))
    part%set_count = 0
    deallocate(part%hex_tag)
    allocate(part%hex_tag(range%nzone))
    data%mode = MODE_ZONES
    data%zone0 = zone0
    call stream_file(part%path, prefix, head, data, part, range, again)
    if (par_max(again%count) > 0) then
      call status%add(prefix//'the file changed while it was read')
      return
    end if

    ! Ids and positions of the node tags used here, from the tags' owners:
    ! [tag, found, id, x, y, z, index in $Nodes].
    ids = [reshape(range%conn(:, lo:lo + nz - 1), [8 * nz]), &
        reshape(part%quads(4:7, :part%nq), [4 * part%nq])]
    call sort_unique(ids)
    allocate(send(1, size(ids)), dest(size(ids)))
    send(1, :) = ids
    do i = 1, size(ids)
      dest(i) = tag_owner(part, ids(i))
    end do
    call par_route_free(send, dest, recv, source)
    deallocate(dest)
    allocate(answer(7, size(recv, 2)))
    do i = 1, size(recv, 2)
      k = find_store(part, recv(1, i))
      if (k == 0) then
        answer(:, i) = [recv(1, i), 0_i8, 0_i8, 0_i8, 0_i8, 0_i8, 0_i8]
      else
        answer(:, i) = [recv(1, i), 1_i8, part%store(6, k), part%store(3:5, k), part%store(2, k)]
      end if
    end do
    deallocate(recv)
    call par_route_free(answer, source, ans)
    deallocate(source)
    if (any(ans(1, :) /= ids)) error stop 'range_add_gmsh: answers out of order'

    ! Hexahedra: every node tag in $Nodes (zone order is rank order).
    nbad = 0
    do i = 1, nz
      do c = 1, 8
        k = sorted_find(ids, range%conn(c, lo + i - 1))
        if (ans(2, k) /= 0) cycle
        nbad = nbad + 1
        if (nbad <= MAX_REPORT) lines(nbad) = prefix//'hexahedron '//i8toa(part%hex_tag(lo + &
            i - 1))//' refers to node '//i8toa(ans(1, k))//', which is not in $Nodes'
      end do
    end do
    call merge_capped(status, prefix, lines, nbad, 'unknown node tags in hexahedra')
    if (par_max(nbad) > 0) return
    ! Used nodes with finite coordinates (in the order of $Nodes).
    do i = 1, part%nstore
      if (part%store(6, i) == 0) cycle
      if (all(ieee_is_finite([(transfer(part%store(2 + j, i), 1.0_rk), j = 1, 3)]))) cycle
      call keyed%add(part%store(2, i), prefix//'node '//i8toa(part%store(1, i))// &
          ' has a coordinate that is not a finite number')
    end do
    call keyed%merge(status, prefix, 'nodes with non-finite coordinates')
    if (par_max(keyed%n) > 0) return
    do i = 1, nz
      do c = 1, 8
        k = sorted_find(ids, range%conn(c, lo + i - 1))
        range%conn(c, lo + i - 1) = node0 + ans(3, k)
        do j = 1, 3
          range%corner_x(j, c, lo + i - 1) = transfer(ans(3 + j, k), 1.0_rk)
        end do
      end do
      range%zone_block(lo + i - 1) = int(find_sorted(part%block_tags, &
          int(range%zone_block(lo + i - 1))), ik)
    end do

    ! The same hexahedron twice: [sorted node key (4), zone, tag] to the owner
    ! of the smallest node's block of ids (key order is rank order).
    allocate(send(6, nz), dest(nz))
    do i = 1, nz
      send(1:4, i) = sorted_key(int(range%conn(:, lo + i - 1) - node0))
      send(5:6, i) = [zfirst + i - 1, part%hex_tag(lo + i - 1)]
      dest(i) = par_block_owner(part%nnode, par_size(), send(1, i) / SHIFT)
    end do
    call par_route_free(send, dest, recv)
    deallocate(dest)
    call sort_order(recv(1:5, :), order)
    nbad = 0
    do i = 2, size(order)
      if (any(recv(1:4, order(i)) /= recv(1:4, order(i - 1)))) cycle
      nbad = nbad + 1
      if (nbad <= MAX_REPORT) lines(nbad) = prefix//'hexahedra '//i8toa(recv(6, order(i - 1)))// &
          ' and '//i8toa(recv(6, order(i)))//' have the same nodes (is a volume in '// &
          'several 3D physical groups?)'
    end do
    deallocate(recv, order)
    call merge_capped(status, prefix, lines, nbad, 'repeated hexahedra')

    ! Orientation: Gmsh and impact3d share the node order.
    allocate(vol(nz))
    nbad = 0
    do i = 1, nz
      vol(i) = hex_volume(range%corner_x(:, :, lo + i - 1))
      if (vol(i) <= 0.0_rk) then
        write(text, '(es12.4)') vol(i)
        nbad = nbad + 1
        if (nbad <= MAX_REPORT) lines(nbad) = prefix//'hexahedron '//i8toa(part%hex_tag(lo + &
            i - 1))//' has volume '//trim(adjustl(text))//' <= 0: its nodes are inverted or '// &
            'degenerate (impact3d does not reorder them)'
      end if
    end do
    call merge_capped(status, prefix, lines, nbad, 'hexahedra with volume <= 0')

    ! Quadrilaterals: node tags in $Nodes (quadrilateral order is rank
    ! order), then [key (2), index, set and tag, ids packed (2)] to the owner
    ! of their smallest node's block of ids.
    nbad = 0
    keyed = keyed_report_t()
    allocate(send(6, part%nq), dest(part%nq))
    m = 0
    do i = 1, part%nq
      unknown = .false.
      do c = 1, 4
        k = sorted_find(ids, part%quads(3 + c, i))
        nid(c) = int(ans(3, k))
        if (ans(2, k) == 0) then
          unknown = .true.
          nbad = nbad + 1
          if (nbad <= MAX_REPORT) lines(nbad) = prefix//'quadrilateral '// &
              i8toa(part%quads(2, i))//' refers to node '//i8toa(part%quads(3 + c, i))// &
              ', which is not in $Nodes'
        end if
      end do
      if (unknown) cycle
      if (any(nid == 0)) then
        call keyed%add(part%quads(1, i), prefix//'quadrilateral '//i8toa(part%quads(2, i))// &
            ' of face set '''//trim(part%set_names(find_sorted(part%set_tags, &
            int(part%quads(3, i)))))//''' matches no hexahedron face')
        cycle
      end if
      m = m + 1
      send(1:2, m) = sorted_key(nid)
      send(3:6, m) = [part%quads(1, i), int(find_sorted(part%set_tags, int(part%quads(3, i))), &
          i8) * SHIFT + part%quads(2, i), int(nid(1), i8) * SHIFT + nid(2), &
          int(nid(3), i8) * SHIFT + nid(4)]
      dest(m) = par_block_owner(part%nnode, par_size(), send(1, m) / SHIFT)
    end do
    call merge_capped(status, prefix, lines, nbad, 'unknown node tags in quadrilaterals')
    send = send(:, :m)
    call par_route_free(send, dest(:m), quads)
    deallocate(dest, ids, ans)
    ! Each quadrilateral's face: the first (smallest 6 (zone - 1) + face)
    ! with its nodes, or the first of those whose orientation agrees, as
    ! build_sets takes it. The hexahedra's faces [key (2), 6 (zone - 1) +
    ! face, ids packed (2)] go to the same owners one face direction at a
    ! time (six rounds of nz records), each quadrilateral keeping its best
    ! so far: best2(1) the first face, best2(2) the first that agrees.
    allocate(best2(2, size(quads, 2)))
    best2 = huge(1_i8)
    do f = 1, 6
      allocate(faces(5, nz), dest(nz))
      do i = 1, nz
        nid = int(range%conn(HEX_FACE_NODES(:, f), lo + i - 1) - node0)
        faces(1:2, i) = sorted_key(nid)
        faces(3:5, i) = [6 * (zfirst - zone0 + i - 2) + f, int(nid(1), i8) * SHIFT + nid(2), &
            int(nid(3), i8) * SHIFT + nid(4)]
        dest(i) = par_block_owner(part%nnode, par_size(), faces(1, i) / SHIFT)
      end do
      call par_route_free(faces, dest, recv)
      deallocate(dest)
      call sort_order(recv(1:3, :), order)
      do i = 1, size(quads, 2)
        fk = quads(1:2, i)
        kk = [quads(5, i) / SHIFT, modulo(quads(5, i), SHIFT), quads(6, i) / SHIFT, &
            modulo(quads(6, i), SHIFT)]
        j = face_lower_bound(recv, order, fk)
        do while (j <= size(order))
          cand = order(j)
          if (any(recv(1:2, cand) /= fk)) exit
          best2(1, i) = min(best2(1, i), recv(3, cand))
          if (same_cycle([int(recv(4, cand) / SHIFT), int(modulo(recv(4, cand), SHIFT)), &
              int(recv(5, cand) / SHIFT), int(modulo(recv(5, cand), SHIFT))], int(kk))) then
            best2(2, i) = min(best2(2, i), recv(3, cand))
            exit
          end if
          j = j + 1
        end do
      end do
      deallocate(recv, order)
    end do
    ! [global zone, 6 (zone - 1) + face, set] to the zone's rank.
    allocate(send(3, size(quads, 2)), dest(size(quads, 2)))
    m = 0
    do i = 1, size(quads, 2)
      if (best2(1, i) == huge(1_i8)) then
        s = int(quads(4, i) / SHIFT)
        call keyed%add(quads(3, i), prefix//'quadrilateral '//i8toa(modulo(quads(4, i), SHIFT))// &
            ' of face set '''//trim(part%set_names(s))//''' matches no hexahedron face')
        cycle
      end if
      m = m + 1
      if (best2(2, i) < huge(1_i8)) best2(1, i) = best2(2, i)
      g = zone0 + (best2(1, i) - 1) / 6 + 1
      send(:, m) = [g, best2(1, i), quads(4, i) / SHIFT]
      dest(m) = par_block_owner(range%nzone_global, par_size(), g)
    end do
    deallocate(quads, best2)
    call keyed%merge(status, prefix, 'quadrilaterals matching no hexahedron face')
    send = send(:, :m)
    call par_route_free(send, dest(:m), entries)
    deallocate(dest)

    ! Face sets: sorted by (set, zone and face), repeats dropped; each set's
    ! places follow the ranks.
    call sort_order(entries([3, 2], :), order)
    entries = entries(:, order)
    deallocate(order)
    allocate(cnt(nset), off(nset))
    cnt = 0
    n = 0
    do i = 1, size(entries, 2)
      if (i > 1) then
        if (all(entries(2:3, i) == entries(2:3, i - 1))) cycle
      end if
      n = n + 1
      entries(:, n) = entries(:, i)
      cnt(entries(3, n)) = cnt(entries(3, n)) + 1
    end do
    do s = 1, nset
      off(s) = par_exscan_i8(cnt(s))
      part%set_count(s) = par_sum(cnt(s))
    end do
    call range_grow_faces(range, 2 * n)
    pos = range%nface
    allocate(key(n), value(4, n))
    cnt = 0
    do i = 1, n
      s = int(entries(3, i))
      cnt(s) = cnt(s) + 1
      k = int(entries(1, i) - range%first) + 1
      f = int(entries(2, i) - 6 * ((entries(2, i) - 1) / 6))
      do c = 1, 2
        if (sets(c, s) == 0) cycle
        pos = pos + 1
        range%face_set(pos) = sets(c, s)
        range%face_zone(pos) = k
        range%face_face(pos) = f
        range%face_ord(pos) = ord0(c, s) + off(s) + cnt(s)
      end do
      do j = 1, 4
        p(:, j) = range%corner_x(:, HEX_FACE_NODES(j, f), k)
      end do
      a = norm2(quad_vector_area(p))
      key(i) = off(s) + cnt(s)
      value(:, i) = [a, a * 0.25_rk * sum(p, dim=2)]
    end do
    range%nface = pos

    ! The summary, its sums in a single reader's order.
    allocate(volume(size(part%block_tags)))
    do c = 1, size(part%block_tags)
      call par_ordered_sum(pack([(zfirst - zone0 + i - 1, i = 1, nz)], &
          range%zone_block(lo:lo + nz - 1) == c), reshape(pack(vol, &
          range%zone_block(lo:lo + nz - 1) == c), [1, count(range%zone_block(lo:lo + nz - 1) &
          == c)]), total(1:1))
      volume(c) = total(1)
    end do
    deallocate(summary)
    allocate(summary(2 + size(part%block_tags) + nset))
    summary(1) = title
    write(summary(2), '(a,i0,a,i0,a,es24.16)') '  ', part%nnode, ' nodes, ', part%nhex, &
        ' zones, volume ', sum(volume)
    n = 2
    do c = 1, size(part%block_tags)
      n = n + 1
      write(summary(n), '(3a,i0,a,es24.16)') '  block ''', trim(part%block_names(c)), &
          ''': ', par_sum(int(count(range%zone_block(lo:lo + nz - 1) == c), i8)), &
          ' zones, volume ', volume(c)
    end do
    do s = 1, nset
      call par_ordered_sum(pack(key, entries(3, :size(key)) == s), reshape(pack(value, &
          spread(entries(3, :size(key)) == s, 1, 4)), [4, count(entries(3, :size(key)) == s)]), &
          total)
      if (total(1) > 0.0_rk) total(2:4) = total(2:4) / total(1)
      n = n + 1
      write(summary(n), '(3a,i0,a,es24.16,a,3es24.16)') '  face set ''', &
          trim(part%set_names(s)), ''': ', part%set_count(s), ' faces, area ', total(1), &
          ', centre', total(2:4)
    end do
    deallocate(part%hex_tag, part%quads, part%store)
  end subroutine range_add_gmsh

  !> First position in order of the faces (sorted by order) whose key is >= fk.
  pure integer function face_lower_bound(faces, order, fk) result(lo)
    integer(i8), intent(in) :: faces(:, :), fk(2)
    integer, intent(in) :: order(:)
    integer :: hi, mid
    lo = 1
    hi = size(order) + 1
    do while (lo < hi)
      mid = (lo + hi) / 2
      if (faces(1, order(mid)) < fk(1) .or. (faces(1, order(mid)) == fk(1) .and. &
          faces(2, order(mid)) < fk(2))) then
        lo = mid + 1
      else
        hi = mid
      end if
    end do
  end function face_lower_bound

end module mesh_gmsh_stream
