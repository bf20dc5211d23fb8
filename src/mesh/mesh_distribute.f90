!> This rank's mesh_t from its zone range (mesh_range), with no array sized
!> by the whole mesh on any rank: the dual graph by matching faces at the
!> block owner of their lowest node, the partition in parallel
!> (parallel_partition), the zones moved to their owners in one all-to-all,
!> a node directory (block owner of each node id: the zones around the node
!> and its owner), the ghost layer fetched from its owners, and the local
!> numbering by sorting global ids. The result is the mesh_t that
!> mesh_build_local makes from the whole mesh with the same zone owners.
module mesh_distribute
  use core_kinds, only: rk, ik, i8
  use core_sort, only: sort_order, sort_unique, sort_values
  use core_timer, only: timers_t
  use mesh_geometry, only: HEX_FACE_NODES
  use mesh_local, only: mesh_t
  use mesh_range, only: mesh_range_t
  use parallel_env, only: par_rank, par_size, par_sum, par_allgather
  use parallel_route, only: par_route, par_route_free, par_block_owner

  use parallel_partition, only: partition_graph
  implicit none
  private
  public :: mesh_distribute_build

  !> What the distribution gave and cost on this rank (its phases are timed
  !> in the run's timers: dual graph, partition, migrate, halo plans).
  type, public :: distribute_stats_t
    integer(i8) :: edge_cut = 0 !< faces between parts
    integer(i8) :: bytes_sent = 0 !< bytes this rank sent in the set-up's all-to-alls
  end type distribute_stats_t

  ! Layout of a zone record (columns of 64-bit integers; reals bit for bit).
  integer, parameter :: R_GID = 1 !< global zone id
  integer, parameter :: R_BLOCK = 2 !< block
  integer, parameter :: R_CONN = 3 !< 8 global node ids
  !> 6 face neighbours: 8 (global id) + (its face), 0 = none
  integer, parameter :: R_NBR = 11
  integer, parameter :: R_X = 17 !< 24 corner coordinates
  integer, parameter :: NREC = 40
  ! A set face: zone gid, set, face, position in the set.
  integer, parameter :: NSETREC = 4
  !> Two ranks in one directory record: node owner * OWNER_BASE + zone owner.
  integer(i8), parameter :: OWNER_BASE = 2_i8**31

contains

  !> Build mesh (and the initial positions of its local nodes) from this
  !> rank's range.
  subroutine mesh_distribute_build(range, partitioner, mesh, coordinates, stats, timers)
    type(mesh_range_t), intent(inout) :: range !< emptied on the way
    character(len=*), intent(in) :: partitioner !< 'scotch' or 'metis' (parallel_partition)
    type(mesh_t), intent(inout) :: mesh
    real(rk), allocatable, intent(out) :: coordinates(:, :) !< (3, mesh%nnode)
    type(distribute_stats_t), intent(out) :: stats
    type(timers_t), intent(inout) :: timers
    integer(i8), allocatable :: nbr(:, :), nbrf(:, :), zrec(:, :), srec(:, :), owned(:, :)
    integer(i8), allocatable :: oset(:, :), ghost(:, :), gset(:, :), adj(:, :), recv(:, :)
    integer(i8), allocatable :: dir_node(:)
    integer, allocatable :: dir_owner(:)
    integer(ik), allocatable :: part(:)
    integer, allocatable :: dest(:), order(:)
    integer :: i

    mesh%nzone_global = range%nzone_global
    mesh%nnode_global = range%nnode_global

    call timers%start('dual graph')
    call face_graph(range, nbr, nbrf, stats%bytes_sent)
    call timers%stop('dual graph')

    call timers%start('partition')
    allocate(part(range%nzone))
    call partition_graph(nbr, part, partitioner)
    call relabel_parts(part)
    call timers%stop('partition')

    call timers%start('migrate')
    ! Zones and their set faces to their owners.
    allocate(zrec(NREC, range%nzone), dest(range%nzone))
    do i = 1, range%nzone
      zrec(R_GID, i) = range%first + i - 1
      zrec(R_BLOCK, i) = range%zone_block(i)
      zrec(R_CONN:R_CONN + 7, i) = range%conn(:, i)
      zrec(R_NBR:R_NBR + 5, i) = 8 * nbr(:, i) + nbrf(:, i)
      zrec(R_X:R_X + 23, i) = transfer(reshape(range%corner_x(:, :, i), [24]), 1_i8, 24)
      dest(i) = int(part(i))
    end do
    deallocate(nbr, nbrf, range%conn, range%corner_x, range%zone_block)
    ! Received by source rank, each source's range in order: by global id.
    call par_route_free(zrec, dest, owned, sent_bytes=stats%bytes_sent)
    deallocate(dest)
    allocate(srec(NSETREC, range%nface), dest(range%nface))
    do i = 1, range%nface
      srec(:, i) = [range%first + range%face_zone(i) - 1, int(range%face_set(i), i8), &
          int(range%face_face(i), i8), range%face_ord(i)]
      dest(i) = int(part(range%face_zone(i)))
    end do
    deallocate(range%face_set, range%face_zone, range%face_face, range%face_ord)
    call par_route_free(srec, dest, recv, sent_bytes=stats%bytes_sent)
    deallocate(dest)
    call sort_order(recv, order)
    oset = recv(:, order)
    deallocate(recv)

    ! Node directory: the zones around each node (with their owners) at the
    ! block owner of the node id, sent back to every rank owning one of them.
    call node_directory(owned, range%nnode_global, adj, dir_node, dir_owner, stats%bytes_sent)

    ! Ghost zones (around the nodes of owned zones, owned elsewhere), fetched
    ! with their set faces.
    call fetch_ghosts(owned, oset, adj, ghost, gset, stats%bytes_sent)
    call timers%stop('migrate')

    call timers%start('halo plans')
    call assemble(owned, oset, ghost, gset, adj, dir_node, dir_owner, range, mesh, &
        coordinates, stats%bytes_sent)
    call timers%stop('halo plans')
    ! Faces between parts: owned zones' faces to ghost zones, counted twice.
    stats%edge_cut = par_sum(int(count(mesh%face_neighbour(:, :mesh%nzone_owned) > &
        mesh%nzone_owned), i8)) / 2
  end subroutine mesh_distribute_build

  !> Renumber the parts so that as many zones as possible stay on the rank
  !> that generated them: each rank names the part holding most of its
  !> range (and how many zones), every rank sees all the (count, part, rank)
  !> triples, and parts go to ranks by decreasing count, first come first
  !> served; parts left over take the ranks left over in increasing order.
  !> The same on every rank, and a partition cut in slabs along the ranges
  !> migrates almost nothing.
  subroutine relabel_parts(part)
    integer(ik), intent(inout) :: part(:)
    integer(ik), allocatable :: counts(:), wish(:, :), label(:)
    integer, allocatable :: order(:)
    integer(i8), allocatable :: key(:, :)
    logical, allocatable :: taken_part(:), taken_rank(:)
    integer :: nrank, i, r, p, k
    nrank = par_size()
    if (nrank == 1) return
    allocate(counts(0:nrank - 1), wish(2, nrank), label(0:nrank - 1))
    counts = 0
    do i = 1, size(part)
      counts(part(i)) = counts(part(i)) + 1
    end do
    p = maxloc(counts, dim=1) - 1
    call par_allgather([int(p, ik), counts(p)], wish)
    ! Decreasing count, then increasing rank.
    allocate(key(2, nrank))
    do r = 1, nrank
      key(:, r) = [-int(wish(2, r), i8), int(r, i8)]
    end do
    call sort_order(key, order)
    allocate(taken_part(0:nrank - 1), taken_rank(0:nrank - 1))
    taken_part = .false.
    taken_rank = .false.
    label = -1
    do k = 1, nrank
      r = order(k) - 1
      p = int(wish(1, order(k)))
      if (wish(2, order(k)) == 0 .or. taken_part(p)) cycle
      label(p) = r
      taken_part(p) = .true.
      taken_rank(r) = .true.
    end do
    r = 0
    do p = 0, nrank - 1
      if (taken_part(p)) cycle
      do while (taken_rank(r))
        r = r + 1
      end do
      label(p) = r
      taken_rank(r) = .true.
    end do
    do i = 1, size(part)
      part(i) = label(part(i))
    end do
  end subroutine relabel_parts

  !> Face neighbours of every zone of the range (global id and face, 0 on the
  !> boundary). Faces between two zones of the range are matched here, through
  !> the range's node -> zone lists; the others, keyed by their sorted node
  !> ids, meet at the block owner of their lowest node, where a face seen
  !> twice joins two zones. (A face with more than two zones, which a
  !> conforming mesh has not, joins each to the highest-id other.)
  subroutine face_graph(range, nbr, nbrf, bytes)
    type(mesh_range_t), intent(in) :: range
    integer(i8), allocatable, intent(out) :: nbr(:, :), nbrf(:, :) !< (6, nzone)
    integer(i8), intent(inout) :: bytes
    integer(i8), allocatable :: send(:, :), recv(:, :), reply(:, :), back(:, :), nodes(:)
    integer, allocatable :: dest(:), source(:), order(:), rdest(:), lconn(:, :), start(:), list(:)
    integer(i8) :: key(4)
    integer :: i, f, m, a, b, j, q, nrecv, other, n, nn, o, g, fn(4)
    n = range%nzone
    allocate(nbr(6, n), nbrf(6, n))
    nbr = 0
    nbrf = 0
    ! The range's nodes numbered locally, and the zones around each.
    allocate(nodes(8 * n))
    nodes = reshape(range%conn, [8 * n])
    call sort_unique(nodes)
    nn = size(nodes)
    allocate(lconn(8, n), start(nn + 1), list(8 * n))
    start = 0
    do i = 1, n
      do j = 1, 8
        lconn(j, i) = find(nodes, range%conn(j, i))
        start(lconn(j, i) + 1) = start(lconn(j, i) + 1) + 1
      end do
    end do
    deallocate(nodes)
    start(1) = 1
    do j = 1, nn
      start(j + 1) = start(j + 1) + start(j)
    end do
    do i = 1, n
      do j = 1, 8
        list(start(lconn(j, i))) = i
        start(lconn(j, i)) = start(lconn(j, i)) + 1
      end do
    end do
    do j = nn, 1, -1
      start(j + 1) = start(j)
    end do
    start(1) = 1
    m = 0
    do i = 1, n
      do f = 1, 6
        fn = lconn(HEX_FACE_NODES(:, f), i)
        do a = start(fn(1)), start(fn(1) + 1) - 1
          o = list(a)
          if (o == i) cycle
          do g = 1, 6
            if (all([(any(lconn(HEX_FACE_NODES(:, g), o) == fn(b)), b = 1, 4)])) then
              nbr(f, i) = range%first + o - 1
              nbrf(f, i) = g
            end if
          end do
        end do
        if (nbr(f, i) == 0) m = m + 1
      end do
    end do
    deallocate(lconn, start, list)
    ! The faces left: on the range's boundary.
    allocate(send(6, m), dest(m))
    m = 0
    do i = 1, n
      do f = 1, 6
        if (nbr(f, i) /= 0) cycle
        key = range%conn(HEX_FACE_NODES(:, f), i)
        call sort_values(key)
        m = m + 1
        send(:, m) = [key, range%first + i - 1, int(f, i8)]
        dest(m) = par_block_owner(range%nnode_global, par_size(), key(1))
      end do
    end do
    call par_route_free(send, dest, recv, source, bytes)
    deallocate(dest)
    nrecv = size(recv, 2)
    call sort_order(recv(1:4, :), order)
    allocate(reply(4, nrecv), rdest(nrecv))
    a = 1
    do while (a <= nrecv)
      b = a
      do while (b < nrecv)
        if (any(recv(1:4, order(b + 1)) /= recv(1:4, order(a)))) exit
        b = b + 1
      end do
      ! Zones a..b share the face; each is joined to the highest-id other.
      do j = a, b
        q = order(j)
        other = 0
        do i = a, b
          if (i == j) cycle
          if (other == 0) then
            other = order(i)
          else if (recv(5, order(i)) > recv(5, other)) then
            other = order(i)
          end if
        end do
        if (other == 0) then
          reply(:, q) = [recv(5, q), recv(6, q), 0_i8, 0_i8]
        else
          reply(:, q) = [recv(5, q), recv(6, q), recv(5, other), recv(6, other)]
        end if
        rdest(q) = source(q)
      end do
      a = b + 1
    end do
    deallocate(recv)
    deallocate(order, source)
    call par_route_free(reply, rdest, back, sent_bytes=bytes)
    do j = 1, size(back, 2)
      i = int(back(1, j) - range%first) + 1
      f = int(back(2, j))
      nbr(f, i) = back(3, j)
      nbrf(f, i) = back(4, j)
    end do
  end subroutine face_graph

  !> adj(:, j) = [node, zone, owners] for every zone around every node of
  !> this rank's owned zones (sorted by node, then zone; owners packs the
  !> node's owner and the zone's: node_owner_of, zone_owner_of);
  !> dir_node/dir_owner: the nodes of this rank's directory block (sorted)
  !> and their owners, the owner of the lowest-id zone around each node.
  subroutine node_directory(owned, nnode_global, adj, dir_node, dir_owner, bytes)
    integer(i8), intent(in) :: owned(:, :)
    integer(i8), intent(in) :: nnode_global
    integer(i8), allocatable, intent(out) :: adj(:, :)
    integer(i8), allocatable, intent(out) :: dir_node(:)
    integer, allocatable, intent(out) :: dir_owner(:)
    integer(i8), intent(inout) :: bytes
    integer(i8), allocatable :: send(:, :), recv(:, :), out(:, :)
    integer, allocatable :: dest(:), order(:), odest(:), source(:)
    integer :: nrank, i, c, m, a, b, j, nout, nd, r, nr, ranks(8), nrec
    integer(i8) :: owner
    nrank = par_size()
    allocate(send(2, 8 * size(owned, 2)), dest(8 * size(owned, 2)))
    m = 0
    do i = 1, size(owned, 2)
      do c = 1, 8
        m = m + 1
        send(:, m) = [owned(R_CONN + c - 1, i), owned(R_GID, i)]
        dest(m) = par_block_owner(nnode_global, nrank, send(1, m))
      end do
    end do
    ! The zone's owner is the rank it came from.
    call par_route_free(send, dest, recv, source, bytes)
    deallocate(dest)
    ! Walked in (node, zone) order through order, not permuted (no copy).
    call sort_order(recv(1:2, :), order)
    nrec = size(recv, 2)
    ! Count the outgoing records: each node's zones, to each distinct owner.
    nout = 0
    nd = 0
    a = 1
    do while (a <= nrec)
      b = group_end(a)
      call distinct_ranks(source(order(a:b)), ranks, nr)
      nout = nout + nr * (b - a + 1)
      nd = nd + 1
      a = b + 1
    end do
    allocate(out(3, nout), odest(nout), dir_node(nd), dir_owner(nd))
    nout = 0
    nd = 0
    a = 1
    do while (a <= nrec)
      b = group_end(a)
      owner = source(order(a))
      nd = nd + 1
      dir_node(nd) = recv(1, order(a))
      dir_owner(nd) = int(owner)
      call distinct_ranks(source(order(a:b)), ranks, nr)
      do r = 1, nr
        do j = a, b
          nout = nout + 1
          out(:, nout) = [recv(1, order(j)), recv(2, order(j)), &
              owner * OWNER_BASE + source(order(j))]
          odest(nout) = ranks(r)
        end do
      end do
      a = b + 1
    end do
    deallocate(recv, order, source)
    ! Each directory rank sends in (node, zone) order and the directory
    ! blocks are in rank order, so what arrives is sorted by (node, zone).
    call par_route_free(out, odest, adj, sent_bytes=bytes)

  contains

    !> The last position of the node group starting at position aa.
    integer function group_end(aa) result(bb)
      integer, intent(in) :: aa
      bb = aa
      do while (bb < nrec)
        if (recv(1, order(bb + 1)) /= recv(1, order(aa))) exit
        bb = bb + 1
      end do
    end function group_end

  end subroutine node_directory

  !> The node's owner in a directory record's owners.
  elemental integer function node_owner_of(owners)
    integer(i8), intent(in) :: owners
    node_owner_of = int(owners / OWNER_BASE)
  end function node_owner_of

  !> The zone's owner in a directory record's owners.
  elemental integer function zone_owner_of(owners)
    integer(i8), intent(in) :: owners
    zone_owner_of = int(modulo(owners, OWNER_BASE))
  end function zone_owner_of

  !> The distinct values of owners (at most 8).
  pure subroutine distinct_ranks(owners, ranks, n)
    integer, intent(in) :: owners(:)
    integer, intent(out) :: ranks(8), n
    integer :: i
    n = 0
    do i = 1, size(owners)
      if (any(ranks(:n) == owners(i))) cycle
      n = n + 1
      ranks(n) = int(owners(i))
    end do
  end subroutine distinct_ranks

  !> Zones around the nodes of owned zones that other ranks own, fetched
  !> from those ranks (sorted by global id), with their set faces.
  subroutine fetch_ghosts(owned, oset, adj, ghost, gset, bytes)
    integer(i8), intent(in) :: owned(:, :), oset(:, :), adj(:, :)
    integer(i8), allocatable, intent(out) :: ghost(:, :), gset(:, :)
    integer(i8), intent(inout) :: bytes
    integer(i8), allocatable :: want(:, :), asked(:, :), reply(:, :), sreply(:, :)
    integer, allocatable :: dest(:), source(:), rdest(:), sdest(:), order(:), sstart(:)
    integer :: me, i, j, k, n, z, ns
    me = par_rank()
    ! Distinct (zone, owner) pairs owned elsewhere.
    n = count(zone_owner_of(adj(3, :)) /= me)
    allocate(want(2, n))
    n = 0
    do j = 1, size(adj, 2)
      if (zone_owner_of(adj(3, j)) == me) cycle
      n = n + 1
      want(:, n) = [adj(2, j), int(zone_owner_of(adj(3, j)), i8)]
    end do
    call sort_order(want, order)
    want = want(:, order)
    k = 0
    do j = 1, n
      if (k > 0) then
        if (want(1, j) == want(1, k)) cycle
      end if
      k = k + 1
      want(:, k) = want(:, j)
    end do
    allocate(dest(k))
    dest = int(want(2, :k))
    call par_route(want(1:1, :k), dest, asked, source, bytes)
    ! Set faces of owned zones: CSR by owned position.
    allocate(sstart(size(owned, 2) + 1))
    sstart = 0
    do j = 1, size(oset, 2)
      z = find(owned(R_GID, :), oset(1, j))
      sstart(z + 1) = sstart(z + 1) + 1
    end do
    sstart(1) = 1
    do z = 1, size(owned, 2)
      sstart(z + 1) = sstart(z + 1) + sstart(z)
    end do
    ! oset is sorted by zone gid as owned is, so set faces of owned zone z
    ! are oset(:, sstart(z):sstart(z+1)-1).
    allocate(reply(NREC, size(asked, 2)), rdest(size(asked, 2)))
    ns = 0
    do j = 1, size(asked, 2)
      z = find(owned(R_GID, :), asked(1, j))
      reply(:, j) = owned(:, z)
      rdest(j) = source(j)
      ns = ns + sstart(z + 1) - sstart(z)
    end do
    allocate(sreply(NSETREC, ns), sdest(ns))
    ns = 0
    do j = 1, size(asked, 2)
      z = find(owned(R_GID, :), asked(1, j))
      do i = sstart(z), sstart(z + 1) - 1
        ns = ns + 1
        sreply(:, ns) = oset(:, i)
        sdest(ns) = source(j)
      end do
    end do
    call par_route(reply, rdest, ghost, sent_bytes=bytes)
    call sort_order(ghost(R_GID, :), order)
    ghost = ghost(:, order)
    call par_route(sreply, sdest, gset, sent_bytes=bytes)
  end subroutine fetch_ghosts

  !> Position of key in the sorted list (0 when absent).
  pure integer function find(list, key) result(pos)
    integer(i8), intent(in) :: list(:), key
    integer :: lo, hi, mid
    lo = 1
    hi = size(list)
    pos = 0
    do while (lo <= hi)
      mid = (lo + hi) / 2
      if (list(mid) == key) then
        pos = mid
        return
      else if (list(mid) < key) then
        lo = mid + 1
      else
        hi = mid - 1
      end if
    end do
  end function find

  !> The local mesh: zones owned then ghost, nodes owned then ghost, each
  !> group by global id; corners, face neighbours, face sets, halo and I/O
  !> plans.
  subroutine assemble(owned, oset, ghost, gset, adj, dir_node, dir_owner, range, mesh, &
      coordinates, bytes)
    integer(i8), intent(in) :: owned(:, :), oset(:, :), ghost(:, :), gset(:, :), adj(:, :)
    integer(i8), intent(in) :: dir_node(:)
    integer, intent(in) :: dir_owner(:)
    type(mesh_range_t), intent(in) :: range
    type(mesh_t), intent(inout) :: mesh
    real(rk), allocatable, intent(out) :: coordinates(:, :)
    integer(i8), intent(inout) :: bytes
    integer(i8), allocatable :: nodes(:), ask(:, :), asked(:, :), reply(:, :), back(:, :)
    integer(i8), allocatable :: zkey(:), sets(:, :)
    integer, allocatable :: nowner(:), dest(:), source(:), order(:), zval(:), nval(:)
    integer, allocatable :: zone_owner(:)
    real(rk) :: x(3, 8)
    integer :: me, nrank, nown, ngh, nz, nn, j, k, c, z, n, a, b, f, nk
    integer(i8) :: rec(NREC), g, last
    me = par_rank()
    nrank = par_size()
    nown = size(owned, 2)
    ngh = size(ghost, 2)
    nz = nown + ngh
    mesh%nzone_owned = nown
    mesh%nzone = nz
    allocate(mesh%zone_gid(nz), mesh%zone_block(nz), zone_owner(nz))
    do z = 1, nz
      rec = zone_record(z)
      mesh%zone_gid(z) = rec(R_GID)
      mesh%zone_block(z) = int(rec(R_BLOCK))
      zone_owner(z) = me
    end do
    ! Ghost zone owners from the node directory's records.
    do j = 1, size(adj, 2)
      if (zone_owner_of(adj(3, j)) == me) cycle
      z = find(mesh%zone_gid(nown + 1:), adj(2, j))
      if (z > 0) zone_owner(nown + z) = zone_owner_of(adj(3, j))
    end do

    ! Local nodes: those of local zones; owners from the directory records
    ! (nodes of owned zones) or asked of the directory (the others).
    allocate(nodes(8 * nz))
    do z = 1, nz
      rec = zone_record(z)
      nodes(8 * z - 7:8 * z) = rec(R_CONN:R_CONN + 7)
    end do
    call sort_unique(nodes)
    nn = size(nodes)
    allocate(nowner(nn))
    nowner = -1
    do j = 1, size(adj, 2)
      n = find(nodes, adj(1, j))
      nowner(n) = node_owner_of(adj(3, j))
    end do
    k = count(nowner < 0)
    allocate(ask(1, k), dest(k))
    k = 0
    do n = 1, nn
      if (nowner(n) >= 0) cycle
      k = k + 1
      ask(1, k) = nodes(n)
      dest(k) = par_block_owner(range%nnode_global, nrank, nodes(n))
    end do
    call par_route(ask, dest, asked, source, bytes)
    allocate(reply(2, size(asked, 2)))
    do j = 1, size(asked, 2)
      reply(:, j) = [asked(1, j), int(dir_owner(find(dir_node, asked(1, j))), i8)]
    end do
    call par_route(reply, source, back, sent_bytes=bytes)
    do j = 1, size(back, 2)
      nowner(find(nodes, back(1, j))) = int(back(2, j))
    end do

    ! Node numbering: owned, then ghosts, each by global id.
    mesh%nnode = nn
    mesh%nnode_owned = count(nowner == me)
    allocate(mesh%node_gid(nn), mesh%node_owner(nn), nval(nn))
    a = 0
    b = mesh%nnode_owned
    do n = 1, nn
      if (nowner(n) == me) then
        a = a + 1
        nval(n) = a
      else
        b = b + 1
        nval(n) = b
      end if
      mesh%node_gid(nval(n)) = nodes(n)
      mesh%node_owner(nval(n)) = nowner(n)
    end do

    allocate(mesh%zone_node(8, nz), coordinates(3, nn))
    do z = 1, nz
      rec = zone_record(z)
      x = reshape(transfer(rec(R_X:R_X + 23), 1.0_rk, 24), [3, 8])
      do c = 1, 8
        n = nval(find(nodes, rec(R_CONN + c - 1)))
        mesh%zone_node(c, z) = n
        coordinates(:, n) = x(:, c)
      end do
    end do

    ! Corners of owned nodes in increasing zone id: the directory's records
    ! (sorted by node, then zone) hold every zone around them.
    allocate(mesh%corner_start(mesh%nnode_owned + 1))
    mesh%corner_start = 0
    do j = 1, size(adj, 2)
      if (node_owner_of(adj(3, j)) /= me) cycle
      n = nval(find(nodes, adj(1, j)))
      mesh%corner_start(n + 1) = mesh%corner_start(n + 1) + 1
    end do
    mesh%corner_start(1) = 1
    do n = 1, mesh%nnode_owned
      mesh%corner_start(n + 1) = mesh%corner_start(n + 1) + mesh%corner_start(n)
    end do
    allocate(mesh%corner_list(mesh%corner_start(mesh%nnode_owned + 1) - 1))
    allocate(zkey(nz), zval(nz))
    call sort_order(mesh%zone_gid, order)
    zkey = mesh%zone_gid(order)
    zval = order
    nk = 0
    last = 0
    do j = 1, size(adj, 2)
      if (node_owner_of(adj(3, j)) /= me) cycle
      n = nval(find(nodes, adj(1, j)))
      z = zval(find(zkey, adj(2, j)))
      do c = 1, 8
        if (mesh%node_gid(mesh%zone_node(c, z)) == adj(1, j)) exit
      end do
      ! Records of one node are consecutive and in zone order.
      if (adj(1, j) /= last) nk = 0
      last = adj(1, j)
      mesh%corner_list(mesh%corner_start(n) + nk) = 8 * (z - 1) + c
      nk = nk + 1
    end do

    ! Face neighbours.
    allocate(mesh%face_neighbour(6, nz), mesh%face_neighbour_face(6, nz))
    do z = 1, nz
      rec = zone_record(z)
      do f = 1, 6
        g = rec(R_NBR + f - 1) / 8
        mesh%face_neighbour_face(f, z) = int(modulo(rec(R_NBR + f - 1), 8_i8))
        if (g == 0) then
          mesh%face_neighbour(f, z) = 0
        else
          k = find(zkey, g)
          if (k > 0) then
            mesh%face_neighbour(f, z) = zval(k)
          else
            mesh%face_neighbour(f, z) = -1
          end if
        end if
      end do
    end do

    ! Face sets of local zones, in each set's global order.
    mesh%nset = range%nset
    allocate(mesh%set_name(mesh%nset), mesh%set_start(mesh%nset + 1))
    mesh%set_name = range%set_name
    allocate(sets(2, size(oset, 2) + size(gset, 2)))
    do j = 1, size(oset, 2)
      sets(:, j) = oset(2:4:2, j)
    end do
    do j = 1, size(gset, 2)
      sets(:, size(oset, 2) + j) = gset(2:4:2, j)
    end do
    call sort_order(sets, order)
    allocate(mesh%set_zone(size(order)), mesh%set_face(size(order)), mesh%set_ord(size(order)))
    mesh%set_start = 0
    do j = 1, size(order)
      k = order(j)
      if (k <= size(oset, 2)) then
        rec(1:NSETREC) = oset(:, k)
      else
        rec(1:NSETREC) = gset(:, k - size(oset, 2))
      end if
      mesh%set_zone(j) = zval(find(zkey, rec(1)))
      mesh%set_face(j) = int(rec(3))
      mesh%set_ord(j) = rec(4)
      mesh%set_start(int(rec(2)) + 1) = mesh%set_start(int(rec(2)) + 1) + 1
    end do
    mesh%set_start(1) = 1
    do k = 1, mesh%nset
      mesh%set_start(k + 1) = mesh%set_start(k + 1) + mesh%set_start(k)
    end do

    call mesh%node_halo%init(mesh%node_gid, mesh%node_owner, mesh%nnode_owned)
    call mesh%zone_halo%init(mesh%zone_gid, zone_owner, mesh%nzone_owned)
    call mesh%node_io%init(mesh%node_gid(1:mesh%nnode_owned), mesh%nnode_global)
    call mesh%zone_io%init(mesh%zone_gid(1:mesh%nzone_owned), mesh%nzone_global)

  contains

    !> The record of local zone z.
    function zone_record(zz) result(r)
      integer, intent(in) :: zz
      integer(i8) :: r(NREC)
      if (zz <= nown) then
        r = owned(:, zz)
      else
        r = ghost(:, zz - nown)
      end if
    end function zone_record

  end subroutine assemble

end module mesh_distribute
